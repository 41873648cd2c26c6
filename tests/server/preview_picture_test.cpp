// The preview's picture (issue 55, item 3): POST .../execution?dry_run=true&picture=true builds the
// first run's discretised sample, plate or tank with the run's own builders and draws it; the
// picture is a PNG the page fetches by URL, and the counts it states are those the run then holds.
// An oversized spec or a build past the time bound is refused with a reason, never a 5xx or a hang.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <filesystem>

#include "views/preview_picture.hpp"
#include "rupture/quantity_text.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {

using test::LiveServer;

std::uint32_t bigEndian32(const std::string& bytes, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at])) << 24 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + 1])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + 2])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + 3]));
}

/// The scenario's example (the form's starting spec), cut to a couple of steps so that it runs in seconds.
Json shortExample(const std::string& scenario) {
  Json inputs = rupture::scenarioSchema(scenario)["examples"][0];
  if (scenario == "elastic-properties") {
    inputs["sample"]["size"] = {4e-7, 4e-7};  // its tests relax the whole sample: a small one
    inputs["sample"]["porosity"] = 0;
    inputs["sample"].erase("pore_radius");
  } else {
    inputs["run"]["max_steps"] = 2;
  }
  if (scenario == "dynamic-tension") inputs["loading"]["initial_velocity"] = "VL";  // no preliminary run
  return inputs;
}

Json pictureOf(httplib::Client& client, const std::string& scenario, const Json& inputs) {
  auto res = test::postJson(client, "/processes/" + scenario + "/execution?dry_run=true&picture=true",
                            Json{{"inputs", inputs}});
  EXPECT_TRUE(res);
  if (!res) return Json();
  EXPECT_EQ(res->status, 200) << res->body;
  return Json::parse(res->body)["picture"];
}

/// The run's own counts for the same spec: its summary after two steps.
Json runSummary(const std::string& scenario, const Json& inputs, const std::filesystem::path& dir) {
  Json spec = inputs;
  spec["scenario"] = scenario;
  rupture::RunControl control;
  control.cacheDirectory = (dir / "cache").string();
  return rupture::runSpec(nlohmann::json(spec), (dir / (scenario + ".h5")).string(), control).summary;
}

class PreviewPictureOf : public testing::TestWithParam<const char*> {};

TEST_P(PreviewPictureOf, IsAPngOfWhatTheRunBuilds) {
  ASSERT_TRUE(test::scenarioAvailable());
  const std::string scenario = GetParam();
  LiveServer live;
  auto client = live.client();
  const Json inputs = shortExample(scenario);
  const Json picture = pictureOf(*client, scenario, inputs);
  ASSERT_EQ(picture["available"], true) << picture.dump();
  ASSERT_TRUE(picture["href"].is_string()) << picture.dump();

  auto png = client->Get(picture["href"].get<std::string>());
  ASSERT_TRUE(png);
  ASSERT_EQ(png->status, 200) << png->body;
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
  const std::string& bytes = png->body;
  ASSERT_GT(bytes.size(), 33u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << "the PNG signature";
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  EXPECT_EQ(bigEndian32(bytes, 16), picture["width"].get<std::uint32_t>());
  EXPECT_EQ(bigEndian32(bytes, 20), picture["height"].get<std::uint32_t>());
  EXPECT_GT(bytes.size(), 5000u) << "a picture of thousands of points, not a blank canvas";

  // The counts it states are the run's.
  test::TempDir dir;
  const Json summary = runSummary(scenario, inputs, dir.path());
  const bool fluid = picture["elements_name"] == "particles";
  const Json& runCount = summary[fluid ? "particles" : "elements"];
  ASSERT_TRUE(runCount.is_number_integer()) << summary.dump();
  EXPECT_EQ(picture["elements"], runCount) << picture.dump();
  if (scenario == std::string("tank-impact")) {
    EXPECT_EQ(picture["plate_nodes"], summary["plate_nodes"]);
  }
  if (!fluid) {
    EXPECT_EQ(picture["bonds"], summary["bonds"]);
  }
  // ... and the caption says them in words.
  EXPECT_NE(picture["caption"].dump().find(rupture::formatQuantity(runCount.get<double>(), "1")), std::string::npos)
      << picture["caption"].dump();
  EXPECT_NE(picture["caption"].dump().find(" m"), std::string::npos) << "sizes in engineering units";
}

INSTANTIATE_TEST_SUITE_P(EveryScenario, PreviewPictureOf,
                         testing::Values("dynamic-tension", "impact", "elastic-properties", "dam-break",
                                         "piston-column", "tank-impact"),
                         [](const testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           std::erase(name, '-');
                           return name;
                         });

TEST(PreviewPicture, OfASweepIsTheFirstRunsAndSaysSo) {
  ASSERT_TRUE(test::scenarioAvailable());
  LiveServer live;
  auto client = live.client();
  const Json body = {{"inputs", test::smallInputs()}, {"sweep", {{"loading.strain_rate", test::twoStrainRates()}}}};
  auto res = test::postJson(*client, test::kExecutePath + "?dry_run=true&picture=true", body);
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const Json d = Json::parse(res->body);
  ASSERT_EQ(d["picture"]["available"], true) << d["picture"].dump();
  EXPECT_EQ(d["picture"]["run_index"], 0);
  EXPECT_EQ(d["picture"]["runs"], 2);
  EXPECT_NE(d["picture"]["note"].get<std::string>().find("first of the job's 2 runs"), std::string::npos);
}

TEST(PreviewPicture, FillsTheSampleCacheSoTheRunReadsTheSampleItShowed) {
  ASSERT_TRUE(test::scenarioAvailable());
  LiveServer live;
  auto client = live.client();
  Json inputs = test::smallInputs();
  inputs["run"]["max_steps"] = 2;
  const Json picture = pictureOf(*client, test::kScenario, inputs);
  ASSERT_EQ(picture["available"], true) << picture.dump();
  EXPECT_EQ(picture["sample_from_cache"], false) << "a fresh server: built";
  EXPECT_EQ(pictureOf(*client, test::kScenario, inputs)["sample_from_cache"], true) << "asked again: read back";
  const std::int64_t id = test::submit(*client, Json{{"inputs", inputs}});
  const Json done = test::waitForJob(*client, id, {"successful", "failed"}, 120);
  ASSERT_EQ(done["status"], "successful") << done.dump();
  const Json run = test::getJson(*client, "/jobs/" + std::to_string(id) + "/runs/0");
  EXPECT_EQ(run["summary"]["sample_from_cache"], 1) << "the run read the sample the preview built";
  EXPECT_EQ(run["summary"]["elements"], picture["elements"]);
}

TEST(PreviewPicture, IsAskedOnlyWithADryRunAndNotDrawnUnlessAsked) {
  ASSERT_TRUE(test::scenarioAvailable());
  LiveServer live;
  auto client = live.client();
  const Json body = {{"inputs", test::smallInputs()}};
  test::expectProblem(test::postJson(*client, test::kExecutePath + "?picture=true", body), 400, "picture");
  test::expectProblem(test::postJson(*client, test::kExecutePath + "?dry_run=true&picture=maybe", body), 400,
                      "picture");
  auto res = test::postJson(*client, test::kExecutePath + "?dry_run=true", body);
  ASSERT_TRUE(res);
  const Json d = Json::parse(res->body);
  EXPECT_EQ(d["picture"]["available"], false);
  EXPECT_NE(d["picture"]["reason"].get<std::string>().find("picture=true"), std::string::npos);
  EXPECT_EQ(test::getJson(*client, "/jobs")["jobs"].size(), 0u) << "a preview queues nothing";
  // A picture no dry run drew is a 404 problem, not a server error.
  auto missing = client->Get("/processes/" + std::string(test::kScenario) + "/previews/0123456789abcdef0123456789abcdef");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
}

TEST(PreviewPicture, OfAnOversizedSpecIsRefusedWithAReasonBeforeAnythingIsBuilt) {
  ASSERT_TRUE(test::scenarioAvailable());
  LiveServer live;
  auto client = live.client();
  Json inputs = test::smallInputs();
  inputs["sample"]["element_radius"] = inputs["sample"]["element_radius"].get<double>() / 30;  // ~900x the elements
  const auto started = std::chrono::steady_clock::now();
  auto res = test::postJson(*client, test::kExecutePath + "?dry_run=true&picture=true", Json{{"inputs", inputs}});
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const Json d = Json::parse(res->body);
  EXPECT_EQ(d["picture"]["available"], false);
  EXPECT_NE(d["picture"]["reason"].get<std::string>().find("sample.element_radius"), std::string::npos)
      << d["picture"].dump();
  EXPECT_GT(d["picture"]["elements_estimated"].get<double>(), d["picture"]["limits"]["max_elements"].get<double>());
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 5.0)
      << "refused from the estimate, not after building";
}

TEST(PreviewPicture, ABuildPastItsTimeBoundIsStoppedAndSaysWhy) {
  ASSERT_TRUE(test::scenarioAvailable());
  Json spec = test::smallInputs();
  spec["scenario"] = test::kScenario;
  spec["sample"]["element_radius"] = spec["sample"]["element_radius"].get<double>() / 3;  // packing takes a while
  const rupture::RunEstimate estimate = rupture::estimateRun(nlohmann::json(spec));
  PicturePolicy policy;
  policy.maxSeconds = 0.05;
  const std::atomic<bool> stopping{false};
  const auto started = std::chrono::steady_clock::now();
  const PreviewPicture picture = previewPicture(spec, estimate, policy, "", "", stopping);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  EXPECT_EQ(picture.doc["available"], false) << picture.doc.dump();
  EXPECT_NE(picture.doc["reason"].get<std::string>().find("longer than the preview allows"), std::string::npos)
      << picture.doc.dump();
  EXPECT_TRUE(picture.png.empty());
  EXPECT_LT(took, 2.0) << "the builder polls the bound";
}

TEST(PreviewPicture, OfValidationSaysThereIsNoSingleSample) {
  const Json spec = {{"scenario", "validation"}, {"case", "piston-column-first-peak"}, {"level", "quick"}};
  const std::atomic<bool> stopping{false};
  rupture::RunEstimate none;
  try {
    const PreviewPicture picture = previewPicture(spec, none, PicturePolicy{}, "", "", stopping);
    EXPECT_EQ(picture.doc["available"], false);
    EXPECT_NE(picture.doc["reason"].get<std::string>().find("no single sample"), std::string::npos)
        << picture.doc.dump();
  } catch (const std::exception& e) {
    FAIL() << "a refusal, not an exception: " << e.what();
  }
}

TEST(PreviewPicture, TheFormShowsThePictureElement) {
  LiveServer live;
  auto client = live.client();
  auto page = client->Get("/processes/" + std::string(test::kScenario) + "?f=html");
  ASSERT_TRUE(page);
  ASSERT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("id=\"preview-picture\""), std::string::npos);
  EXPECT_NE(page->body.find("id=\"preview-caption\""), std::string::npos);
  EXPECT_NE(page->body.find("&picture=true"), std::string::npos) << "the script asks for the picture";
}

}  // namespace
}  // namespace rupture::server
