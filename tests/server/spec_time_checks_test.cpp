// Issue 55 item 7: what the spec alone decides is refused at POST with a 400 naming the field (no
// job is made), not found by the sample builder in the worker; and a failed run's job does not
// show a full progress bar.
#include <gtest/gtest.h>

#include "jobs/job_store.hpp"
#include "routes/documents.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {

TEST(SpecTimeChecks, BadGeometryGets400NamingTheField) {
  ASSERT_TRUE(test::scenarioAvailable());
  test::LiveServer live;
  auto client = live.client();

  Json narrow = test::smallInputs();
  narrow["sample"]["size"][0] = 2e-8;  // the reported case: narrower than one element (R_DE = 12 nm)
  Json doc = test::expectProblem(test::postJson(*client, test::kExecutePath, {{"inputs", narrow}}), 400, "sample.size[0]");
  EXPECT_NE(doc.value("detail", "").find("at least one element wide"), std::string::npos) << doc.dump();

  Json gauge = test::smallInputs();
  gauge["sample"].erase("porosity");
  gauge["sample"].erase("pore_radius");
  gauge["sample"]["size"][0] = 4e-8;  // wider than an element, shorter than two of the largest
  doc = test::expectProblem(test::postJson(*client, test::kExecutePath, {{"inputs", gauge}}), 400, "sample.size[0]");
  EXPECT_NE(doc.value("detail", "").find("both loaded faces"), std::string::npos) << doc.dump();

  Json pores = test::smallInputs();
  pores["sample"]["porosity"] = 0.45;
  pores["sample"]["pore_radius"] = {3.5e-7, 3.5e-7};
  doc = test::expectProblem(test::postJson(*client, test::kExecutePath, {{"inputs", pores}}), 400, "sample.porosity");
  EXPECT_NE(doc.value("detail", "").find("do not fit side by side"), std::string::npos) << doc.dump();

  Json inclusions = test::smallInputs();
  inclusions["sample"]["inclusions"] = {{"volume_fraction", 0.45}, {"radius", {3.5e-7, 3.5e-7}}};
  doc = test::expectProblem(test::postJson(*client, test::kExecutePath, {{"inputs", inclusions}}), 400,
                            "sample.inclusions.volume_fraction");
  EXPECT_NE(doc.value("detail", "").find("do not fit side by side"), std::string::npos) << doc.dump();

  // A sweep whose one point is bad is refused whole, naming the field.
  Json sweep = test::smallInputs();
  Json body = {{"inputs", sweep}, {"sweep", {{"sample.element_radius", {1.2e-8, 6e-7}}}}};  // 1.2 um elements in 1 um
  auto res = test::postJson(*client, test::kExecutePath, body);
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400) << res->body;
  EXPECT_NE(res->body.find("sample.size[0]"), std::string::npos) << res->body;

  Json impact = Json::parse(test::readText(std::filesystem::path(RUPTURE_SOURCE_DIR) / "examples" / "impact-branching-pmb.json"));
  impact.erase("scenario");
  impact["loading"]["tractions"][1]["min"] = {0, -0.01};
  impact["loading"]["tractions"][1]["max"] = {0.1, -0.005};
  doc = test::expectProblem(test::postJson(*client, "/processes/impact/execution", {{"inputs", impact}}), 400,
                            "loading.tractions[1]");
  EXPECT_NE(doc.value("detail", "").find("a box overlapping the sample"), std::string::npos) << doc.dump();

  EXPECT_EQ(test::getJson(*client, "/jobs")["numberMatched"], 0) << "no job for a bad submission";
}

TEST(SpecTimeChecks, AFailedRunsJobShowsTheProgressItReachedNotAFullBar) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  NewJob job;
  job.processId = "dynamic-tension";
  job.name = "fails";
  job.sweepMode = "grid";
  job.sweptPaths = Json::array({"loading.strain_rate"});
  job.inputs = Json::parse(R"({"loading": {"strain_rate": 1}})");
  job.sweep = Json::parse(R"({"loading.strain_rate": [1, 2]})");
  for (int k = 1; k <= 2; ++k)
    job.runs.emplace_back(Json::array({k}), Json{{"scenario", "dynamic-tension"}, {"loading", {{"strain_rate", k}}}});
  const auto id = store.createJob(job);
  ASSERT_TRUE(store.startRun({id, 0}));
  store.finishSuccessful({id, 0}, Json::object(), "jobs/1/run-0.h5");
  ASSERT_TRUE(store.startRun({id, 1}));
  store.setProgress({{{id, 1}, 0.4, ""}});
  store.finishFailed({id, 1}, "boom at 40 %");

  const auto record = store.job(id);
  ASSERT_TRUE(record);
  EXPECT_EQ(record->status, Status::Failed);
  EXPECT_NEAR(record->progress, (1.0 + 0.4) / 2, 1e-9);
  const auto runs = store.runs(id);
  const Json status = statusInfo(*record, &runs);
  EXPECT_EQ(status["status"], "failed");
  EXPECT_EQ(status["progress"], 70) << status.dump();
  EXPECT_EQ(runDocument(*record, *store.run({id, 1}))["progress"], 40);
  EXPECT_EQ(runDocument(*record, *store.run({id, 0}))["progress"], 100);

  // A run that fails after its last step (writing its file, say) still shows less than a full bar.
  NewJob single = job;
  single.runs.resize(1);
  const auto late = store.createJob(single);
  ASSERT_TRUE(store.startRun({late, 0}));
  store.setProgress({{{late, 0}, 1.0, ""}});
  store.finishFailed({late, 0}, "disk full");
  const auto lateRecord = store.job(late);
  const auto lateRuns = store.runs(late);
  EXPECT_LT(statusInfo(*lateRecord, &lateRuns)["progress"].get<int>(), 100);
  EXPECT_LT(runDocument(*lateRecord, *store.run({late, 0}))["progress"].get<int>(), 100);
}

}  // namespace
}  // namespace rupture::server
