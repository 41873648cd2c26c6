#include "studies/refinement.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <regex>

#include "common/log.hpp"
#include "rupture/run.hpp"
#include "studies/summary.hpp"

namespace rupture::server {
namespace {

ApiError refineError(const std::string& field, const Json& value, const std::string& detail,
                     const Json& allowed = Json()) {
  Json extra{{"in", "body"}, {"value", value}};
  if (!allowed.is_null()) extra["allowed"] = allowed;
  return ApiError(400, problem::kInvalidRequest, "Invalid refine", detail, field, extra);
}

double relativeChange(double a, double b) {
  const double scale = std::max(std::abs(a), std::abs(b));
  return scale > 0 ? std::abs(b - a) / scale : 0.0;
}

}  // namespace

Json RefinePlan::toJson() const {
  return Json{{"path", path},           {"quantity", quantity},
              {"max_runs", maxRuns},    {"tolerance", tolerance},
              {"spacing", logSpacing ? "log" : "linear"}, {"per_round", perRound},
              {"integer", integer}};
}

RefinePlan RefinePlan::fromJson(const Json& doc) {
  RefinePlan p;
  p.path = doc.value("path", "");
  p.quantity = doc.value("quantity", "");
  p.maxRuns = doc.value("max_runs", 0);
  p.tolerance = doc.value("tolerance", kDefaultRefineTolerance);
  p.logSpacing = doc.value("spacing", "linear") == "log";
  p.perRound = doc.value("per_round", 1);
  p.integer = doc.value("integer", false);
  return p;
}

std::optional<RefinePlan> parseRefinePlan(const Json* member, const std::string& scenario, const SweepPlan& sweep,
                                          int runsPerPoint, std::size_t initialRuns, std::size_t maxRuns) {
  if (!member || member->is_null()) return std::nullopt;
  if (!member->is_object()) {
    throw refineError("refine", *member,
                      "refine must be an object such as {\"path\": \"loading.strain_rate\", \"quantity\": "
                      "\"peak_stress\", \"max_runs\": 8, \"tolerance\": 0.1}");
  }
  static const Json allowedMembers = Json::array({"path", "quantity", "max_runs", "tolerance", "spacing", "per_round"});
  for (const auto& [key, value] : member->items()) {
    if (std::find(allowedMembers.begin(), allowedMembers.end(), key) == allowedMembers.end()) {
      throw refineError("refine." + key, value, "unknown member '" + key + "' in refine; allowed: " + allowedMembers.dump(),
                        allowedMembers);
    }
  }
  RefinePlan plan;
  Json swept = Json::array();
  for (const SweepAxis& a : sweep.axes) swept.push_back(a.path);
  const auto path = member->find("path");
  if (path == member->end() || !path->is_string()) {
    throw refineError("refine.path", path == member->end() ? Json("(missing)") : *path,
                      "refine.path must name the swept path to refine; swept paths: " + swept.dump(), swept);
  }
  plan.path = path->get<std::string>();
  const SweepAxis* axis = nullptr;
  for (const SweepAxis& a : sweep.axes) {
    if (a.path == plan.path) axis = &a;
  }
  if (!axis) {
    throw refineError("refine.path", *path,
                      "refine.path '" + plan.path + "' is not swept; refinement adds values to a swept path: " +
                          swept.dump(),
                      swept);
  }
  if (sweep.mode == SweepMode::Zip && sweep.axes.size() > 1) {
    throw refineError("refine.path", *path,
                      "refinement needs a grid sweep (a zip sweep moves its paths together, so a value between two "
                      "of one path has no partner in the others)",
                      Json::array({"grid"}));
  }
  double lo = 0, hi = 0;
  bool allIntegers = true;
  for (std::size_t i = 0; i < axis->values.size(); ++i) {
    const Json& v = axis->values[i];
    if (!v.is_number() || v.is_boolean()) {
      throw refineError("refine.path", *path,
                        "refine.path '" + plan.path + "' has a value that is not a number (" + v.dump() +
                            "); only numeric paths can be refined");
    }
    if (!v.is_number_integer()) allIntegers = false;
    const double x = v.get<double>();
    lo = i ? std::min(lo, x) : x;
    hi = i ? std::max(hi, x) : x;
  }
  if (axis->values.size() < 2) {
    throw refineError("refine.path", *path, "refine.path '" + plan.path + "' needs at least two swept values to refine between");
  }
  nlohmann::json schema;
  try {
    schema = rupture::scenarioSchema(scenario);
  } catch (const std::exception&) {
    schema = nlohmann::json::object();
  }
  const nlohmann::json* node = schemaNodeAt(schema, plan.path);
  plan.integer = (node && isIntegerSchema(*node)) || (!node && allIntegers);

  const auto quantity = member->find("quantity");
  static const std::regex scalarName(R"(^[A-Za-z][A-Za-z0-9_.]{0,99}$)");
  if (quantity == member->end() || !quantity->is_string() ||
      !std::regex_match(quantity->get<std::string>(), scalarName)) {
    throw refineError("refine.quantity", quantity == member->end() ? Json("(missing)") : *quantity,
                      "refine.quantity must name a numeric result scalar of the runs, e.g. \"peak_stress\"");
  }
  plan.quantity = quantity->get<std::string>();
  // Only a number the scenario declares can be refined on: anything else would end the study with
  // "no successful run reported it" after the first round has run.
  if (const rupture::ScenarioInfo* info = rupture::findScenario(scenario)) {
    Json allowed = Json::array();
    for (const rupture::ResultField& f : info->summary) {
      if (!f.unit.empty() && f.name.back() != '*') allowed.push_back(f.name);
    }
    const rupture::ResultField* field = rupture::findResultField(info->summary, plan.quantity);
    if (!field || field->unit.empty()) {
      throw refineError("refine.quantity", *quantity,
                        "refine.quantity '" + plan.quantity + "' is not a numeric result of the " + scenario +
                            " scenario; allowed: " + allowed.dump(),
                        allowed);
    }
  }

  const auto budget = member->find("max_runs");
  const long long most = static_cast<long long>(maxRuns) - static_cast<long long>(initialRuns);
  if (budget == member->end() || !budget->is_number_integer() || budget->get<long long>() < runsPerPoint ||
      budget->get<long long>() > most) {
    const Json value = budget == member->end() ? Json("(missing)") : *budget;
    throw refineError("refine.max_runs", value,
                      "refine.max_runs (runs refinement may add) must be an integer from " + std::to_string(runsPerPoint) +
                          " (one point" + (runsPerPoint > 1 ? ", with its replicates" : "") + ") to " +
                          std::to_string(std::max(0LL, most)) + " (this server's --max-runs " + std::to_string(maxRuns) +
                          " less the " + std::to_string(initialRuns) + " initial runs), got " + value.dump(),
                      Json{{"minimum", runsPerPoint}, {"maximum", std::max(0LL, most)}});
  }
  plan.maxRuns = budget->get<int>();

  if (const auto tol = member->find("tolerance"); tol != member->end()) {
    if (!tol->is_number() || tol->is_boolean() || !(tol->get<double>() > 0 && tol->get<double>() < 1)) {
      throw refineError("refine.tolerance", *tol,
                        "refine.tolerance is the relative change between neighbours below which no point is added: "
                        "a number in (0, 1), got " + tol->dump(),
                        Json{{"exclusiveMinimum", 0}, {"exclusiveMaximum", 1}});
    }
    plan.tolerance = tol->get<double>();
  }
  std::string spacing = "auto";
  if (const auto sp = member->find("spacing"); sp != member->end()) {
    if (!sp->is_string() || (*sp != "auto" && *sp != "log" && *sp != "linear")) {
      throw refineError("refine.spacing", *sp, "refine.spacing must be \"auto\", \"log\" or \"linear\", got " + sp->dump(),
                        Json::array({"auto", "log", "linear"}));
    }
    spacing = sp->get<std::string>();
  }
  if (spacing == "log" && !(lo > 0)) {
    throw refineError("refine.spacing", "log",
                      "log spacing needs every value of '" + plan.path + "' > 0; the smallest is " + formatNumber(lo),
                      Json::array({"auto", "linear"}));
  }
  plan.logSpacing = spacing == "log" || (spacing == "auto" && lo > 0 && hi >= 10 * lo);
  if (const auto pr = member->find("per_round"); pr != member->end()) {
    if (!pr->is_number_integer() || pr->get<long long>() < 1 || pr->get<long long>() > kMaxRefinePerRound) {
      throw refineError("refine.per_round", *pr,
                        "refine.per_round (points added per series and round) must be an integer from 1 to " +
                            std::to_string(kMaxRefinePerRound) + ", got " + pr->dump(),
                        Json{{"minimum", 1}, {"maximum", kMaxRefinePerRound}});
    }
    plan.perRound = pr->get<int>();
  }
  return plan;
}

RefinementRound planRefinementRound(const RefinePlan& plan, std::size_t axis,
                                    const std::vector<RefinementObservation>& observations, int runsAdded,
                                    int runsPerPoint) {
  RefinementRound round;
  // Series (the other swept values) -> refined value -> quantities of its successful runs.
  struct Series {
    Json swept;  // a representative swept array
    std::map<double, std::vector<double>> samples;
    std::vector<double> allValues;  // every value present, whatever its runs' outcome
  };
  std::vector<std::string> order;
  std::map<std::string, Series> series;
  bool anyQuantity = false;
  for (const RefinementObservation& o : observations) {
    if (!o.swept.is_array() || axis >= o.swept.size() || !o.swept[axis].is_number()) continue;
    Json key = o.swept;
    key[axis] = nullptr;
    const std::string k = key.dump();
    if (!series.count(k)) {
      order.push_back(k);
      series[k].swept = o.swept;
    }
    const double x = o.swept[axis].get<double>();
    series[k].allValues.push_back(x);
    if (o.successful && o.quantity && std::isfinite(*o.quantity)) {
      series[k].samples[x].push_back(*o.quantity);
      anyQuantity = true;
    }
  }
  if (!anyQuantity) {
    round.stopReason = "no successful run reported '" + plan.quantity + "' as a number";
    return round;
  }
  struct Candidate {
    std::size_t series;
    RefinementPoint point;
  };
  std::vector<Candidate> candidates;
  bool aboveTolerance = false;
  for (std::size_t s = 0; s < order.size(); ++s) {
    const Series& ser = series[order[s]];
    std::vector<std::pair<double, double>> means;  // value -> mean quantity, ascending
    for (const auto& [x, qs] : ser.samples) {
      double sum = 0;
      for (double q : qs) sum += q;
      means.emplace_back(x, sum / qs.size());
    }
    std::vector<Candidate> mine;
    for (std::size_t i = 1; i < means.size(); ++i) {
      const auto [a, qa] = means[i - 1];
      const auto [b, qb] = means[i];
      const double change = relativeChange(qa, qb);
      if (!(change > plan.tolerance)) continue;
      aboveTolerance = true;
      if (b - a <= kRefineResolution * std::max(std::abs(a), std::abs(b))) continue;
      double value = plan.logSpacing && a > 0 ? std::sqrt(a * b) : 0.5 * (a + b);
      if (plan.integer) value = std::round(value);
      if (!(value > a && value < b)) continue;
      // A value already present (a point whose runs all failed sits between a and b) is not added again.
      if (std::find(ser.allValues.begin(), ser.allValues.end(), value) != ser.allValues.end()) continue;
      RefinementPoint p;
      p.swept = ser.swept;
      p.swept[axis] = plan.integer ? Json(static_cast<long long>(value)) : Json(value);
      p.value = value;
      p.a = a;
      p.b = b;
      p.change = change;
      mine.push_back({s, p});
    }
    std::stable_sort(mine.begin(), mine.end(),
                     [](const Candidate& x, const Candidate& y) { return x.point.change > y.point.change; });
    if (mine.size() > static_cast<std::size_t>(plan.perRound)) mine.resize(static_cast<std::size_t>(plan.perRound));
    candidates.insert(candidates.end(), mine.begin(), mine.end());
  }
  if (candidates.empty()) {
    round.stopReason = aboveTolerance
                           ? "the neighbours that still change by more than the tolerance are too close to split"
                           : "every neighbour change is at most the tolerance " + formatNumber(plan.tolerance);
    return round;
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& x, const Candidate& y) { return x.point.change > y.point.change; });
  int budget = plan.maxRuns - runsAdded;
  for (const Candidate& c : candidates) {
    if (budget < runsPerPoint) break;
    round.points.push_back(c.point);
    budget -= runsPerPoint;
  }
  if (round.points.empty()) {
    round.stopReason = "max_runs reached: " + std::to_string(runsAdded) + " of " + std::to_string(plan.maxRuns) +
                       " runs added, and a point needs " + std::to_string(runsPerPoint);
  }
  return round;
}

// ---------------------------------------------------------------------------------------------

RefinementDriver::RefinementDriver(JobStore& store, Executor& executor, double maxElements, double maxMemoryBytes,
                                   double maxSteps)
    : m_store(store), m_executor(executor), m_maxElements(maxElements), m_maxMemoryBytes(maxMemoryBytes),
      m_maxSteps(maxSteps) {}

RefinementDriver::~RefinementDriver() { stop(); }

void RefinementDriver::start() {
  std::lock_guard lock(m_mutex);
  if (m_thread.joinable() || m_stopping) return;
  m_thread = std::thread([this] { loop(); });
}

void RefinementDriver::stop() {
  {
    std::lock_guard lock(m_mutex);
    m_stopping = true;
  }
  m_wake.notify_all();
  if (m_thread.joinable()) m_thread.join();
}

void RefinementDriver::loop() {
  std::unique_lock lock(m_mutex);
  while (!m_stopping) {
    lock.unlock();
    try {
      refineDueJobs();
    } catch (const std::exception& e) {
      logLine(std::string("refinement: ") + e.what());
    }
    lock.lock();
    m_wake.wait_for(lock, std::chrono::milliseconds(500), [this] { return m_stopping; });
  }
}

void RefinementDriver::refineDueJobs() {
  for (std::int64_t id : m_store.jobsAwaitingRefinement()) {
    {
      std::lock_guard lock(m_mutex);
      if (m_stopping) return;
    }
    refineJob(id);
  }
}

void RefinementDriver::refineJob(std::int64_t jobId) {
  auto job = m_store.job(jobId);
  if (!job || !job->study.is_object()) return;
  Json study = job->study;
  Json& record = study["refinement"];
  auto close = [&](const std::string& reason) {
    record["state"] = "done";
    record["stopped"] = reason;
    m_store.setStudy(jobId, study);
    logLine("job " + std::to_string(jobId) + ": refinement done: " + reason);
  };
  if (job->status == Status::Dismissed) {
    close("the job was dismissed");
    return;
  }
  const RefinePlan plan = RefinePlan::fromJson(study["refine"]);
  ReplicatePlan replicates;
  if (study.contains("replicates") && study["replicates"].is_object()) {
    replicates.count = study["replicates"].value("count", 1);
    replicates.vary = study["replicates"].value("vary", "");
  }
  std::vector<std::string> paths;
  for (const auto& p : job->sweptPaths) paths.push_back(p.get<std::string>());
  const std::size_t axis = std::find(paths.begin(), paths.end(), plan.path) - paths.begin();
  if (axis >= paths.size()) {
    close("the refined path is not swept");
    return;
  }
  std::vector<RefinementObservation> observations;
  for (const RunRecord& run : m_store.runs(jobId)) {
    RefinementObservation o;
    o.swept = run.swept;
    o.successful = run.status == Status::Successful;
    if (o.successful && run.summary.is_object()) {
      const Json* q = findAtPath(run.summary, plan.quantity);
      if (q && q->is_number() && !q->is_boolean()) o.quantity = q->get<double>();
    }
    observations.push_back(std::move(o));
  }
  const int runsAdded = record.value("runs_added", 0);
  const RefinementRound round = planRefinementRound(plan, axis, observations, runsAdded, replicates.count);
  if (round.points.empty()) {
    close(round.stopReason);
    return;
  }
  // Build and validate the new runs as a submission would.
  std::vector<std::pair<Json, Json>> runs;
  std::vector<int> replicateIndex;
  SweepPlan onePoint;
  onePoint.mode = SweepMode::Grid;
  for (const std::string& p : paths) onePoint.axes.push_back({p, Json::array({nullptr})});
  const int roundNumber = record.value("rounds", 0) + 1;
  int next = job->runsTotal;
  Json added = Json::array();
  try {
    for (const RefinementPoint& point : round.points) {
      for (std::size_t a = 0; a < paths.size(); ++a) onePoint.axes[a].values = Json::array({point.swept[a]});
      std::vector<SweepPoint> points = expandSweep(job->processId, job->inputs, onePoint, 1);
      const std::vector<ReplicatedPoint> expanded = expandReplicates(std::move(points), replicates, job->processId);
      std::vector<SweepPoint> specs;
      for (const ReplicatedPoint& rp : expanded) specs.push_back(rp.point);
      const Executor::RankLimit ranks = m_executor.rankLimit();
      validateSweepPoints(specs, onePoint, m_maxElements, m_maxMemoryBytes, m_maxSteps, ranks.ranks, ranks.why);
      Json indices = Json::array();
      for (const ReplicatedPoint& rp : expanded) {
        runs.emplace_back(rp.point.swept, rp.point.spec);
        replicateIndex.push_back(rp.replicate);
        indices.push_back(next++);
      }
      Json group = Json::object();
      for (std::size_t a = 0; a < paths.size(); ++a) {
        if (a != axis) group[paths[a]] = point.swept[a];
      }
      added.push_back({{"value", point.swept[axis]},
                       {"between", Json::array({point.a, point.b})},
                       {"change", point.change},
                       {"round", roundNumber},
                       {"group", group},
                       {"runs", indices}});
    }
  } catch (const std::exception& e) {
    close(std::string("a refined point is not a valid run: ") + e.what());
    return;
  }
  record["state"] = "pending";
  record["rounds"] = roundNumber;
  record["runs_added"] = runsAdded + static_cast<int>(runs.size());
  if (!record.contains("points") || !record["points"].is_array()) record["points"] = Json::array();
  for (const auto& p : added) record["points"].push_back(p);
  const std::vector<int> indices = m_store.appendRuns(jobId, runs, replicateIndex, study);
  logLine("job " + std::to_string(jobId) + ": refinement round " + std::to_string(roundNumber) + " adds " +
          std::to_string(indices.size()) + " run(s) on " + plan.path);
  m_executor.resubmit(jobId, indices);
}

}  // namespace rupture::server
