// Studies without a server: Student t quantiles, replicate statistics against the rows, the
// refinement planner on a synthetic quantity, the rate-dependence analysis on a synthetic power law,
// the replicate and refine request checks, and the refinement driver's rounds across a restart.
#include <cmath>

#include <gtest/gtest.h>

#include "jobs/job_store.hpp"
#include "studies/rate_dependence.hpp"
#include "studies/refinement.hpp"
#include "studies/replicate_statistics.hpp"
#include "jobs/replicates.hpp"
#include "server_test_support.hpp"
#include "studies/student_t.hpp"
#include "views/svg_plot.hpp"

namespace rupture::server {
namespace {

TEST(StudentT, QuantilesMatchTheTables) {
  // Two-sided 95 % (p = 0.975) and 99 % (p = 0.995) values of standard t tables.
  EXPECT_NEAR(studentTQuantile(0.975, 1), 12.706, 1e-3);
  EXPECT_NEAR(studentTQuantile(0.975, 2), 4.303, 1e-3);
  EXPECT_NEAR(studentTQuantile(0.975, 4), 2.776, 1e-3);
  EXPECT_NEAR(studentTQuantile(0.975, 9), 2.262, 1e-3);
  EXPECT_NEAR(studentTQuantile(0.975, 30), 2.042, 1e-3);
  EXPECT_NEAR(studentTQuantile(0.995, 5), 4.032, 1e-3);
  EXPECT_NEAR(studentTQuantile(0.975, 1e6), 1.960, 1e-3);  // the normal limit
  EXPECT_NEAR(studentTQuantile(0.025, 9), -2.262, 1e-3);    // symmetry
  EXPECT_NEAR(studentTCdf(studentTQuantile(0.9, 3), 3), 0.9, 1e-12);
  // dof 1 is the Cauchy distribution: F(t) = 1/2 + atan(t)/pi.
  EXPECT_NEAR(studentTCdf(2.5, 1), 0.5 + std::atan(2.5) / M_PI, 1e-12);
}

TEST(ReplicateStatistics, SampleMeanSdAndInterval) {
  const ScalarStatistics s = describeSample({1.0, 2.0, 6.0});
  EXPECT_EQ(s.n, 3);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  ASSERT_TRUE(s.sd);
  EXPECT_NEAR(*s.sd, std::sqrt(7.0), 1e-12);  // ((4 + 1 + 9) / 2)
  ASSERT_TRUE(s.ciHalfWidth);
  EXPECT_NEAR(*s.ciHalfWidth, 4.302653 * std::sqrt(7.0) / std::sqrt(3.0), 1e-5);
  const ScalarStatistics one = describeSample({5.0});
  EXPECT_EQ(one.n, 1);
  EXPECT_FALSE(one.sd);
  EXPECT_FALSE(one.ciHalfWidth);
}

SummaryTable twoPointsThreeReplicates() {
  SummaryTable t;
  t.jobId = 7;
  t.sweptPaths = {"loading.strain_rate"};
  t.scalarNames = {"peak_stress", "note"};
  t.replicated = true;
  const double values[2][3] = {{10, 12, 14}, {20, 26, 0}};
  int run = 0;
  for (int p = 0; p < 2; ++p) {
    for (int r = 0; r < 3; ++r) {
      SummaryRow row;
      row.run = run++;
      row.replicate = r;
      row.swept = Json::array({p == 0 ? 1e5 : 1e6});
      row.status = p == 1 && r == 2 ? Status::Failed : Status::Successful;  // one replicate fails
      row.scalars = row.status == Status::Successful ? Json{{"peak_stress", values[p][r]}, {"note", "text"}} : Json::object();
      t.rows.push_back(row);
    }
  }
  return t;
}

TEST(ReplicateStatistics, PointsAggregateTheirSuccessfulReplicatesOnly) {
  const SummaryTable t = twoPointsThreeReplicates();
  const auto points = aggregateReplicates(t);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0].runs, (std::vector<int>{0, 1, 2}));
  const ScalarStatistics* a = points[0].find("peak_stress");
  ASSERT_TRUE(a);
  EXPECT_EQ(a->n, 3);
  EXPECT_DOUBLE_EQ(a->mean, 12);
  EXPECT_NEAR(*a->sd, 2, 1e-12);
  EXPECT_NEAR(*a->ciHalfWidth, 4.302653 * 2 / std::sqrt(3.0), 1e-5);
  EXPECT_FALSE(points[0].find("note"));  // text has no statistics
  const ScalarStatistics* b = points[1].find("peak_stress");
  ASSERT_TRUE(b);
  EXPECT_EQ(b->n, 2);  // the failed replicate is excluded, and n says so
  EXPECT_DOUBLE_EQ(b->mean, 23);
  EXPECT_NEAR(*b->ciHalfWidth, 12.706205 * std::sqrt(18.0) / std::sqrt(2.0), 1e-4);
  EXPECT_EQ(points[1].excluded, Json::parse(R"([{"run": 5, "status": "failed"}])"));

  const Json doc = aggregateJson(t, points);
  EXPECT_EQ(doc["aggregate"], "replicates");
  EXPECT_EQ(doc["rows"][1]["n_runs"], 3);
  EXPECT_EQ(doc["rows"][1]["n_successful"], 2);
  EXPECT_EQ(doc["rows"][1]["peak_stress"]["n"], 2);
  EXPECT_NEAR(doc["rows"][0]["peak_stress"]["ci95_low"].get<double>(), 12 - 4.302653 * 2 / std::sqrt(3.0), 1e-5);
  const std::string csv = aggregateCsv(t, points);
  EXPECT_EQ(csv.substr(0, csv.find("\r\n")),
            "loading.strain_rate,n_runs [1],n_successful [1],peak_stress.mean,peak_stress.sd,peak_stress.ci95_low,"
            "peak_stress.ci95_high,peak_stress.ci95_half_width,peak_stress.n [1]");
  EXPECT_NE(csv.find("\r\n1000000.0,3,2,23.0,"), std::string::npos) << csv;
  // The per-replicate rows stay available, with their replicate index.
  const Json rows = summaryJson(t);
  EXPECT_EQ(rows["rows"][4]["replicate"], 1);
  EXPECT_EQ(summaryCsv(t).substr(0, 28), "run,status,replicate,loading");
}

TEST(ReplicateStatistics, MeansTableCarriesUnitsAndDrawsTheIntervalsAsErrorBars) {
  SummaryTable t = twoPointsThreeReplicates();
  t.info["loading.strain_rate"] = {"1/s", "Strain rate", ""};
  t.info["peak_stress"] = {"Pa", "Peak stress", "Maximum of the mean boundary stress"};
  const auto points = aggregateReplicates(t);
  const SummaryTable means = meansTable(t, points);
  ASSERT_EQ(means.rows.size(), 2u);
  // Derived columns: in the scalar's unit (n dimensionless), labelled after it.
  ASSERT_TRUE(means.hasColumn(ciHalfWidthColumn("peak_stress")));
  EXPECT_EQ(ciHalfWidthColumn("peak_stress"), "peak_stress.ci95_half_width");
  EXPECT_EQ(means.columnInfo("peak_stress").unit, "Pa");
  EXPECT_EQ(means.columnInfo("peak_stress.sd").unit, "Pa");
  EXPECT_EQ(means.columnInfo("peak_stress.ci95_half_width").unit, "Pa");
  EXPECT_EQ(means.columnInfo("peak_stress.ci95_half_width").label, "Peak stress (95 % CI half-width)");
  EXPECT_EQ(means.columnInfo("peak_stress.n").unit, "1");
  EXPECT_FALSE(means.hasColumn("note.sd"));  // text has no statistics
  EXPECT_DOUBLE_EQ(means.value(means.rows[1], "peak_stress").get<double>(), 23);
  EXPECT_EQ(means.value(means.rows[1], "peak_stress.n"), 2);
  EXPECT_NEAR(means.value(means.rows[0], "peak_stress.ci95_half_width").get<double>(), 4.302653 * 2 / std::sqrt(3.0), 1e-5);
  // The aggregate JSON and CSV carry the units too.
  const Json doc = aggregateJson(t, points);
  EXPECT_EQ(doc["columns"][0]["unit"], "1/s");
  EXPECT_EQ(doc["units"]["peak_stress"], "Pa");
  const std::string csv = aggregateCsv(t, points);
  EXPECT_EQ(csv.substr(0, csv.find(",n_runs")), "loading.strain_rate [1/s]");
  EXPECT_NE(csv.find(",peak_stress.ci95_half_width [Pa],peak_stress.n [1]\r\n"), std::string::npos) << csv;
  // One error bar per point that has an interval (both have n >= 2).
  PlotRequest plot;
  plot.x = "loading.strain_rate";
  plot.y = "peak_stress";
  plot.yError = ciHalfWidthColumn("peak_stress");
  const std::string svg = summarySvg(means, plot);
  std::size_t bars = 0;
  for (std::size_t p = svg.find("class=\"error-bar\""); p != std::string::npos; p = svg.find("class=\"error-bar\"", p + 1)) ++bars;
  EXPECT_EQ(bars, 2u);
  EXPECT_NE(svg.find("Peak stress ["), std::string::npos);
}

// -- refinement planner ------------------------------------------------------------------------

std::vector<RefinementObservation> observe(const std::vector<double>& rates, double (*q)(double)) {
  std::vector<RefinementObservation> out;
  for (double r : rates) out.push_back({Json::array({r}), true, q(r)});
  return out;
}

double steepBetween1e6And1e7(double rate) { return rate < 2e6 ? 1.0 : (rate < 5e6 ? 1.5 : 4.0); }

TEST(RefinementPlanner, SplitsOnlyTheSteepestPairAtItsGeometricMean) {
  RefinePlan plan;
  plan.path = "loading.strain_rate";
  plan.quantity = "peak_stress";
  plan.maxRuns = 10;
  plan.tolerance = 0.05;
  plan.logSpacing = true;
  // 1e5 -> 1e6: no change; 1e6 -> 1e7: from 1 to 4 (change 0.75); 1e7 -> 1e8: 4 -> 4.
  const auto round = planRefinementRound(plan, 0, observe({1e5, 1e6, 1e7, 1e8}, steepBetween1e6And1e7), 0, 1);
  ASSERT_EQ(round.points.size(), 1u);
  EXPECT_DOUBLE_EQ(round.points[0].a, 1e6);
  EXPECT_DOUBLE_EQ(round.points[0].b, 1e7);
  EXPECT_NEAR(round.points[0].value, std::sqrt(1e13), 1e-3);
  EXPECT_NEAR(round.points[0].change, 0.75, 1e-12);
  // Linear spacing takes the arithmetic mean.
  plan.logSpacing = false;
  const auto linear = planRefinementRound(plan, 0, observe({1e5, 1e6, 1e7, 1e8}, steepBetween1e6And1e7), 0, 1);
  ASSERT_EQ(linear.points.size(), 1u);
  EXPECT_DOUBLE_EQ(linear.points[0].value, 5.5e6);
}

TEST(RefinementPlanner, RepeatsUntilTheBudgetAndStopsThere) {
  RefinePlan plan;
  plan.path = "x";
  plan.quantity = "q";
  plan.maxRuns = 6;  // three points of two replicates each
  plan.tolerance = 1e-6;
  plan.logSpacing = true;
  // A smooth power law changes everywhere: refinement goes on until the budget is spent.
  auto q = [](double x) { return std::pow(x, 0.5); };
  std::vector<RefinementObservation> obs;
  for (double x : {1.0, 100.0}) {
    for (int r = 0; r < 2; ++r) obs.push_back({Json::array({x}), true, q(x)});
  }
  int added = 0;
  std::vector<double> values;
  for (int round = 0; round < 10; ++round) {
    const auto next = planRefinementRound(plan, 0, obs, added, 2);
    if (next.points.empty()) {
      EXPECT_NE(next.stopReason.find("max_runs reached"), std::string::npos) << next.stopReason;
      break;
    }
    ASSERT_EQ(next.points.size(), 1u);
    for (const auto& p : next.points) {
      values.push_back(p.value);
      for (int r = 0; r < 2; ++r) obs.push_back({p.swept, true, q(p.value)});
      added += 2;
    }
  }
  EXPECT_EQ(added, 6);
  ASSERT_EQ(values.size(), 3u);
  EXPECT_NEAR(values[0], 10, 1e-9);  // sqrt(1 * 100)
  // x^0.5 changes equally across (1, 10) and (10, 100): the first of equals (the lower) is split,
  // then (10, 100), whose change is now the largest.
  EXPECT_NEAR(values[1], std::sqrt(10.0), 1e-9);
  EXPECT_NEAR(values[2], std::sqrt(1000.0), 1e-9);
}

TEST(RefinementPlanner, StopsWhenEveryChangeIsWithinTolerance) {
  RefinePlan plan;
  plan.path = "x";
  plan.quantity = "q";
  plan.maxRuns = 100;
  plan.tolerance = 0.2;
  plan.logSpacing = false;
  const auto round = planRefinementRound(
      plan, 0, observe({1, 2, 3}, [](double x) { return 10 + x; }), 0, 1);  // changes 1/12, 1/13
  EXPECT_TRUE(round.points.empty());
  EXPECT_NE(round.stopReason.find("tolerance"), std::string::npos);
  // Failed runs and runs without the quantity do not count; none at all ends it with a reason.
  std::vector<RefinementObservation> none = {{Json::array({1}), false, std::nullopt}, {Json::array({2}), true, std::nullopt}};
  EXPECT_NE(planRefinementRound(plan, 0, none, 0, 1).stopReason.find("no successful run"), std::string::npos);
}

TEST(RefinementPlanner, EachSeriesIsRefinedOnItsOwn) {
  RefinePlan plan;
  plan.path = "rate";
  plan.quantity = "q";
  plan.maxRuns = 10;
  plan.tolerance = 0.1;
  plan.logSpacing = true;
  std::vector<RefinementObservation> obs;
  // Series "A" jumps between 10 and 100, series "B" between 100 and 1000.
  for (double r : {1.0, 10.0, 100.0, 1000.0}) {
    obs.push_back({Json::array({r, "A"}), true, r < 50 ? 1.0 : 3.0});
    obs.push_back({Json::array({r, "B"}), true, r < 500 ? 1.0 : 2.0});
  }
  const auto round = planRefinementRound(plan, 0, obs, 0, 1);
  ASSERT_EQ(round.points.size(), 2u);
  EXPECT_EQ(round.points[0].swept[1], "A");  // the larger change first
  EXPECT_DOUBLE_EQ(round.points[0].a, 10);
  EXPECT_EQ(round.points[1].swept[1], "B");
  EXPECT_DOUBLE_EQ(round.points[1].a, 100);
  // With budget for one point, only the largest change is split.
  plan.maxRuns = 1;
  const auto one = planRefinementRound(plan, 0, obs, 0, 1);
  ASSERT_EQ(one.points.size(), 1u);
  EXPECT_EQ(one.points[0].swept[1], "A");
}

// -- rate dependence ---------------------------------------------------------------------------

TEST(RateDependence, RecoversPlateauDoublingAndSlopesOfAPowerLaw) {
  // sigma = 100 MPa below 1e6 /s, then 100 MPa (rate / 1e6)^(1/3) above: a plateau, then an
  // energy-limited branch; doubling where (rate / 1e6)^(1/3) = 2, i.e. 8e6 /s.
  auto sigma = [](double rate) { return 1e8 * std::max(1.0, std::cbrt(rate / 1e6)); };
  std::vector<RateSample> samples;
  for (double rate : {1e4, 1e5, 1e6, 1e7, 1e8}) {
    // Three replicates scattered by +-1 % around the law.
    samples.push_back({rate, {sigma(rate) * 0.99, sigma(rate), sigma(rate) * 1.01}});
  }
  const Json r = rateDependenceSeries(samples);
  EXPECT_NEAR(r["plateau"]["value"].get<double>(), 1e8, 1e-6 * 1e8);
  EXPECT_EQ(r["plateau"]["n_points"], 3);  // 1e4, 1e5, 1e6; 1e7 is 215 % of it
  EXPECT_EQ(r["plateau"]["n_runs"], 9);
  EXPECT_NEAR(r["plateau"]["scatter_relative"].get<double>(), 0.01 * std::sqrt(6.0 / 8.0) / 1.0, 1e-9);
  EXPECT_NEAR(r["doubling_rate"].get<double>(), 8e6, 1e-6 * 8e6);
  ASSERT_EQ(r["slopes"].size(), 4u);
  EXPECT_NEAR(r["slopes"][0]["slope"].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(r["slopes"][3]["slope"].get<double>(), 1.0 / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(r["slopes"][3]["from"].get<double>(), 1e7);

  // An inertial branch (slope 1) that never doubles within the sweep: null, with the reason.
  std::vector<RateSample> flat = {{1e5, {1e8}}, {1e6, {1.05e8}}, {1e7, {1.5e8}}};
  const Json f = rateDependenceSeries(flat);
  EXPECT_TRUE(f["doubling_rate"].is_null());
  EXPECT_NE(f["doubling_reason"].get<std::string>().find("not reached"), std::string::npos);
  EXPECT_TRUE(f["plateau"]["scatter_sd"].is_number());  // 1e5 and 1e6 are within 10 %
  const Json inertial = rateDependenceSeries({{1e6, {1e8}}, {1e7, {1e9}}});
  EXPECT_NEAR(inertial["slopes"][0]["slope"].get<double>(), 1.0, 1e-12);
}

TEST(RateDependence, OneSeriesPerInitialVelocityField) {
  SummaryTable t;
  t.sweptPaths = {"loading.strain_rate", "loading.initial_velocity"};
  t.scalarNames = {"peak_stress"};
  int run = 0;
  for (double rate : {1e5, 1e6, 1e7}) {
    for (const char* v : {"V0", "VL"}) {
      SummaryRow row;
      row.run = run++;
      row.status = Status::Successful;
      row.swept = Json::array({rate, v});
      row.scalars = {{"peak_stress", std::string(v) == "V0" ? 1e8 * rate / 1e5 : 1e8}};
      t.rows.push_back(row);
    }
  }
  const Json doc = rateDependence(t, aggregateReplicates(t));
  EXPECT_EQ(doc["rate_path"], "loading.strain_rate");
  EXPECT_EQ(doc["units"]["doubling_rate"], "1/s");
  ASSERT_EQ(doc["series"].size(), 2u);
  EXPECT_EQ(doc["series"][0]["group"]["loading.initial_velocity"], "V0");
  EXPECT_NEAR(doc["series"][0]["slopes"][0]["slope"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(doc["series"][0]["doubling_rate"].get<double>(), 2e5, 1e-3);
  EXPECT_NEAR(doc["series"][1]["slopes"][1]["slope"].get<double>(), 0.0, 1e-12);
  EXPECT_TRUE(doc["series"][1]["doubling_rate"].is_null());
  t.sweptPaths = {"sample.porosity", "loading.initial_velocity"};
  EXPECT_TRUE(rateDependence(t, aggregateReplicates(t)).is_null());  // no rate swept
}

// -- request checks ----------------------------------------------------------------------------

SweepPlan rateSweep(const Json& values) {
  Json sweep = {{"loading.strain_rate", values}};
  return parseSweepPlan(&sweep, nullptr);
}

void expectBadRequest(const std::function<void()>& f, const std::string& field, const std::string& says) {
  try {
    f();
    ADD_FAILURE() << "no error for " << field;
  } catch (const ApiError& e) {
    EXPECT_EQ(e.status(), 400);
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

TEST(StudyRequests, ReplicatesAreCheckedAndExpandedFromTheBaseValue) {
  ASSERT_TRUE(test::scenarioAvailable());
  const SweepPlan sweep = rateSweep({1e6, 1e7});
  const std::string sc = "dynamic-tension";
  Json ok = {{"count", 3}, {"vary", "sample.seed"}};
  const ReplicatePlan plan = parseReplicatePlan(&ok, sc, sweep);
  EXPECT_EQ(plan.count, 3);
  const auto points = expandSweep(sc, test::smallInputs(), sweep, 100);
  const auto runs = expandReplicates(points, plan, sc);
  ASSERT_EQ(runs.size(), 6u);
  const long long base = test::smallInputs()["sample"]["seed"].get<long long>();
  for (std::size_t k = 0; k < runs.size(); ++k) {
    EXPECT_EQ(runs[k].replicate, static_cast<int>(k % 3));
    EXPECT_EQ(runs[k].point.spec["sample"]["seed"], base + static_cast<long long>(k % 3));
    EXPECT_EQ(runs[k].point.swept, points[k / 3].swept);
  }
  Json count0 = {{"count", 0}, {"vary", "sample.seed"}};
  expectBadRequest([&] { parseReplicatePlan(&count0, sc, sweep); }, "replicates.count", "from 1 to 100");
  Json count101 = {{"count", 101}, {"vary", "sample.seed"}};
  expectBadRequest([&] { parseReplicatePlan(&count101, sc, sweep); }, "replicates.count", "got 101");
  Json notInteger = {{"count", 2}, {"vary", "sample.porosity"}};
  expectBadRequest([&] { parseReplicatePlan(&notInteger, sc, sweep); }, "replicates.vary", "sample.seed");
  Json unknown = {{"count", 2}, {"vary", "sample.nope"}};
  expectBadRequest([&] { parseReplicatePlan(&unknown, sc, sweep); }, "replicates.vary", "not an integer field");
  Json extra = {{"count", 2}, {"vary", "sample.seed"}, {"seeds", 3}};
  expectBadRequest([&] { parseReplicatePlan(&extra, sc, sweep); }, "replicates.seeds", "allowed: count, vary");
  Json swept = {{"loading.strain_rate", {1e6}}, {"sample.seed", {1, 2}}};
  const SweepPlan seedSweep = parseSweepPlan(&swept, nullptr);
  expectBadRequest([&] { parseReplicatePlan(&ok, sc, seedSweep); }, "replicates.vary", "also swept");
}

TEST(StudyRequests, RefineFieldsAreChecked) {
  ASSERT_TRUE(test::scenarioAvailable());
  const std::string sc = "dynamic-tension";
  const SweepPlan sweep = rateSweep({1e5, 1e6, 1e7});
  Json ok = {{"path", "loading.strain_rate"}, {"quantity", "peak_stress"}, {"max_runs", 4}, {"tolerance", 0.1}};
  const auto plan = parseRefinePlan(&ok, sc, sweep, 2, 6, 100);
  ASSERT_TRUE(plan);
  EXPECT_TRUE(plan->logSpacing);  // auto: positive values spanning two decades
  EXPECT_FALSE(plan->integer);
  auto with = [&](const char* key, const Json& value) {
    Json body = ok;
    body[key] = value;
    return body;
  };
  Json b;
  b = with("path", "loading.initial_velocity");
  expectBadRequest([&] { parseRefinePlan(&b, sc, sweep, 1, 3, 100); }, "refine.path", "is not swept");
  b = with("max_runs", 1);
  expectBadRequest([&] { parseRefinePlan(&b, sc, sweep, 2, 6, 100); }, "refine.max_runs", "from 2");
  b = with("max_runs", 95);
  expectBadRequest([&] { parseRefinePlan(&b, sc, sweep, 1, 6, 100); }, "refine.max_runs", "to 94");
  b = with("tolerance", 0);
  expectBadRequest([&] { parseRefinePlan(&b, sc, sweep, 1, 3, 100); }, "refine.tolerance", "(0, 1)");
  b = with("spacing", "cubic");
  expectBadRequest([&] { parseRefinePlan(&b, sc, sweep, 1, 3, 100); }, "refine.spacing", "\"auto\", \"log\"");
  b = with("quantity", "");
  expectBadRequest([&] { parseRefinePlan(&b, sc, sweep, 1, 3, 100); }, "refine.quantity", "result scalar");
  b = with("quantity", "nope");  // well formed, but no result the scenario declares
  expectBadRequest([&] { parseRefinePlan(&b, sc, sweep, 1, 3, 100); }, "refine.quantity", "\"peak_stress\"");
  b = with("quantity", "stop_reason");  // declared, but text
  expectBadRequest([&] { parseRefinePlan(&b, sc, sweep, 1, 3, 100); }, "refine.quantity", "not a numeric result");
  b = with("per_round", 17);
  expectBadRequest([&] { parseRefinePlan(&b, sc, sweep, 1, 3, 100); }, "refine.per_round", "1 to 16");
  b = with("step", 2);
  expectBadRequest([&] { parseRefinePlan(&b, sc, sweep, 1, 3, 100); }, "refine.step", "unknown member");
  const SweepPlan one = rateSweep({1e6});
  expectBadRequest([&] { parseRefinePlan(&ok, sc, one, 1, 1, 100); }, "refine.path", "at least two");
}

// -- the refinement driver over the store, across a restart ------------------------------------

class RecordingExecutor : public Executor {
public:
  void start() override {}
  void enqueue(std::int64_t, int) override {}
  void resubmit(std::int64_t, const std::vector<int>& indices) override {
    submitted.insert(submitted.end(), indices.begin(), indices.end());
  }
  std::optional<JobRecord> dismiss(std::int64_t) override { return std::nullopt; }
  void requestStop() override {}
  void shutdown() override {}
  const char* name() const override { return "recording"; }
  int workers() const override { return 1; }
  int threadsPerRun() const override { return 1; }
  RankLimit rankLimit() const override { return {1, "a test executor"}; }
  bool waitingForDisk() const override { return false; }
  int unrecordedOutcomes() const override { return 0; }
  std::filesystem::path jobDir(std::int64_t) const override { return {}; }
  std::vector<int> submitted;
};

TEST(RefinementDriver, RoundsSurviveAReopenedStoreAndStopAtTheBudget) {
  ASSERT_TRUE(test::scenarioAvailable());
  test::TempDir dir;
  const std::string db = (dir.path() / "db.sqlite").string();
  const SweepPlan sweep = rateSweep({1e5, 1e7});
  Json refine = {{"path", "loading.strain_rate"}, {"quantity", "peak_stress"}, {"max_runs", 2}, {"tolerance", 0.01}};
  NewJob job;
  job.processId = "dynamic-tension";
  job.sweepMode = "grid";
  job.sweptPaths = Json::array({"loading.strain_rate"});
  job.inputs = test::smallInputs();
  for (const auto& p : expandSweep(job.processId, job.inputs, sweep, 10)) job.runs.emplace_back(p.swept, p.spec);
  job.study = {{"refine", parseRefinePlan(&refine, job.processId, sweep, 1, 2, 100)->toJson()},
               {"refinement", {{"state", "pending"}, {"rounds", 0}, {"runs_added", 0}, {"points", Json::array()}}}};
  auto peak = [](double rate) { return 1e8 * std::cbrt(rate / 1e5); };
  std::int64_t id = 0;
  {
    JobStore store(db);
    id = store.createJob(job);
    RecordingExecutor executor;
    RefinementDriver driver(store, executor, 1e9);
    driver.refineDueJobs();
    EXPECT_TRUE(executor.submitted.empty());  // the initial runs have not finished
    for (int k = 0; k < 2; ++k) {
      ASSERT_TRUE(store.startRun({id, k}));
      store.finishSuccessful({id, k}, Json{{"peak_stress", peak(k ? 1e7 : 1e5)}}, "x.h5");
    }
    EXPECT_EQ(store.job(id)->status, Status::Running);  // refinement is due: not finished yet
    driver.refineDueJobs();
    EXPECT_EQ(executor.submitted, (std::vector<int>{2}));
  }
  // The server stops here, with round 1's run accepted: a new server finds it, and the record.
  JobStore store(db);
  EXPECT_EQ(store.queuedRuns().size(), 1u);
  auto reopened = store.job(id);
  ASSERT_TRUE(reopened);
  const Json& points = reopened->study["refinement"]["points"];
  ASSERT_EQ(points.size(), 1u);
  EXPECT_NEAR(points[0]["value"].get<double>(), 1e6, 1e-3);
  EXPECT_EQ(points[0]["between"], Json::array({1e5, 1e7}));
  EXPECT_EQ(points[0]["round"], 1);
  EXPECT_EQ(store.run({id, 2})->spec["loading"]["strain_rate"].get<double>(), points[0]["value"].get<double>());
  RecordingExecutor executor;
  RefinementDriver driver(store, executor, 1e9);
  driver.refineDueJobs();
  EXPECT_TRUE(executor.submitted.empty());  // run 2 is still queued
  ASSERT_TRUE(store.startRun({id, 2}));
  store.finishSuccessful({id, 2}, Json{{"peak_stress", peak(1e6)}}, "x.h5");
  driver.refineDueJobs();
  ASSERT_EQ(executor.submitted, (std::vector<int>{3}));
  ASSERT_TRUE(store.startRun({id, 3}));
  store.finishSuccessful({id, 3}, Json{{"peak_stress", peak(store.run({id, 3})->spec["loading"]["strain_rate"].get<double>())}},
                         "x.h5");
  driver.refineDueJobs();  // the budget (2 runs) is spent
  EXPECT_EQ(executor.submitted.size(), 1u);
  const auto done = store.job(id);
  EXPECT_EQ(done->study["refinement"]["state"], "done");
  EXPECT_EQ(done->study["refinement"]["runs_added"], 2);
  EXPECT_NE(done->study["refinement"]["stopped"].get<std::string>().find("max_runs"), std::string::npos);
  EXPECT_EQ(done->status, Status::Successful);
  EXPECT_EQ(done->runsTotal, 4);
}

}  // namespace
}  // namespace rupture::server
