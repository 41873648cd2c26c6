// Sweep expansion without the engine: grid and zip counts and order, paths, limits.
#include <gtest/gtest.h>

#include "jobs/sweep.hpp"

namespace rupture::server {
namespace {

Json baseInputs() {
  return Json::parse(R"({"dimension": 2, "sample": {"length": 0.01},
                         "loading": {"strain_rate": 1e6, "initial_velocity": "VL"}, "run": {}})");
}

ApiError expectError(const std::function<void()>& f) {
  try {
    f();
  } catch (const ApiError& e) {
    return e;
  }
  ADD_FAILURE() << "no ApiError thrown";
  return ApiError(0, "", "", "");
}

TEST(SweepExpansion, GridIsTheCartesianProductFirstPathSlowest) {
  Json sweep = Json::parse(R"({"loading.strain_rate": [1e5, 1e6, 1e7],
                               "loading.initial_velocity": ["V0", "VL", "VH"]})");
  SweepPlan plan = parseSweepPlan(&sweep, nullptr);
  ASSERT_EQ(plan.mode, SweepMode::Grid);
  EXPECT_EQ(runCount(plan), 9u);
  auto points = expandSweep("dynamic-tension", baseInputs(), plan, 1000);
  ASSERT_EQ(points.size(), 9u);
  EXPECT_EQ(points[0].swept, Json::parse(R"([1e5, "V0"])"));
  EXPECT_EQ(points[1].swept, Json::parse(R"([1e5, "VL"])"));
  EXPECT_EQ(points[3].swept, Json::parse(R"([1e6, "V0"])"));
  EXPECT_EQ(points[8].swept, Json::parse(R"([1e7, "VH"])"));
  EXPECT_EQ(points[4].spec["loading"]["strain_rate"], 1e6);
  EXPECT_EQ(points[4].spec["loading"]["initial_velocity"], "VL");
  EXPECT_EQ(points[4].spec["scenario"], "dynamic-tension");
  EXPECT_EQ(points[4].spec["sample"]["length"], 0.01);  // untouched members are kept
}

TEST(SweepExpansion, ZipPairsElementWise) {
  Json sweep = Json::parse(R"({"loading.strain_rate": [1e5, 1e6, 1e7],
                               "loading.initial_velocity": ["V0", "VL", "VH"]})");
  Json mode = "zip";
  SweepPlan plan = parseSweepPlan(&sweep, &mode);
  EXPECT_EQ(runCount(plan), 3u);
  auto points = expandSweep("dynamic-tension", baseInputs(), plan, 1000);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[2].swept, Json::parse(R"([1e7, "VH"])"));
}

TEST(SweepExpansion, NoSweepIsOneRunOfTheInputs) {
  SweepPlan plan = parseSweepPlan(nullptr, nullptr);
  auto points = expandSweep("dynamic-tension", baseInputs(), plan, 1000);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0].swept, Json::array());
  EXPECT_EQ(points[0].spec["loading"]["initial_velocity"], "VL");
}

TEST(SweepExpansion, NewLeafUnderAnExistingParentIsAllowed) {
  Json sweep = Json::parse(R"({"run.max_strain": [0.01, 0.02]})");
  auto points = expandSweep("dynamic-tension", baseInputs(), parseSweepPlan(&sweep, nullptr), 1000);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[1].spec["run"]["max_strain"], 0.02);
}

TEST(SweepExpansion, MissingParentNamesThePath) {
  Json sweep = Json::parse(R"({"loadin.strain_rate": [1e5]})");
  ApiError e = expectError([&] { expandSweep("dynamic-tension", baseInputs(), parseSweepPlan(&sweep, nullptr), 10); });
  EXPECT_EQ(e.status(), 400);
  EXPECT_EQ(e.field(), "loadin.strain_rate");
  EXPECT_NE(std::string(e.what()).find("'loadin' does not exist"), std::string::npos) << e.what();
}

TEST(SweepExpansion, PathThroughAScalarIsRejected) {
  Json sweep = Json::parse(R"({"dimension.x": [1]})");
  ApiError e = expectError([&] { expandSweep("dynamic-tension", baseInputs(), parseSweepPlan(&sweep, nullptr), 10); });
  EXPECT_EQ(e.field(), "dimension.x");
}

TEST(SweepExpansion, TooManyRunsIsRejectedBeforeExpanding) {
  Json sweep = Json::object();
  Json many = Json::array();
  for (int i = 0; i < 1000; ++i) many.push_back(i);
  sweep["loading.strain_rate"] = many;
  sweep["sample.length"] = many;
  sweep["run.a"] = many;
  sweep["run.b"] = many;
  sweep["run.c"] = many;
  sweep["run.d"] = many;
  sweep["run.e"] = many;  // 1000^7 overflows 64 bits: must saturate, not wrap
  SweepPlan plan = parseSweepPlan(&sweep, nullptr);
  EXPECT_EQ(runCount(plan), std::numeric_limits<std::size_t>::max());
  ApiError e = expectError([&] { expandSweep("dynamic-tension", baseInputs(), plan, 1000); });
  EXPECT_EQ(e.status(), 400);
  EXPECT_EQ(e.type(), problem::kTooManyRuns);

  Json small = Json::parse(R"({"loading.strain_rate": [1, 2, 3], "sample.length": [1, 2]})");
  EXPECT_NO_THROW(expandSweep("dynamic-tension", baseInputs(), parseSweepPlan(&small, nullptr), 6));
  EXPECT_THROW(expandSweep("dynamic-tension", baseInputs(), parseSweepPlan(&small, nullptr), 5), ApiError);
}

TEST(SweepExpansion, MalformedSweepsAreRejectedWithThePath) {
  auto fieldOf = [](const char* sweepText, const char* modeText = nullptr) {
    Json sweep = Json::parse(sweepText);
    Json mode = modeText ? Json::parse(modeText) : Json();
    return expectError([&] { parseSweepPlan(&sweep, modeText ? &mode : nullptr); }).field();
  };
  EXPECT_EQ(fieldOf(R"({"loading.strain_rate": []})"), "loading.strain_rate");
  EXPECT_EQ(fieldOf(R"({"loading.strain_rate": 5})"), "loading.strain_rate");
  EXPECT_EQ(fieldOf(R"({"loading..strain_rate": [1]})"), "loading..strain_rate");
  EXPECT_EQ(fieldOf(R"({"scenario": ["x"]})"), "scenario");
  EXPECT_EQ(fieldOf(R"({"loading": [{}], "loading.strain_rate": [1]})"), "loading.strain_rate");
  EXPECT_EQ(fieldOf(R"([1, 2])"), "sweep");
  EXPECT_EQ(fieldOf(R"({"a.b": [1, 2], "a.c": [1]})", R"("zip")"), "a.c");
  EXPECT_EQ(fieldOf(R"({"a.b": [1]})", R"("diagonal")"), "sweep_mode");
}

TEST(SweepExpansion, ArrayIndicesInPaths) {
  Json inputs = Json::parse(R"({"sample": {"size": [0.01, 0.005]}})");
  Json sweep = Json::parse(R"({"sample.size.1": [0.001, 0.002]})");
  auto points = expandSweep("s", inputs, parseSweepPlan(&sweep, nullptr), 10);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[1].spec["sample"]["size"], Json::parse("[0.01, 0.002]"));
  Json bad = Json::parse(R"({"sample.size.5": [1]})");
  EXPECT_THROW(expandSweep("s", inputs, parseSweepPlan(&bad, nullptr), 10), ApiError);
  const Json* found = findAtPath(points[0].spec, "sample.size.1");
  ASSERT_NE(found, nullptr);
  EXPECT_EQ(*found, 0.001);
}

}  // namespace
}  // namespace rupture::server
