// The job's HTML page in a real browser (ctest label "browser"): Debian's chromium, headless,
// loads it from a live server and the job's rows, its summary table and its status must be in the
// DOM it builds. Skipped only when chromium is absent (deploy/setup.sh installs it).
#include <gtest/gtest.h>

#include <cstdlib>

#include "server_test_support.hpp"
#include "support/png_probe.hpp"

namespace rupture::server {
namespace {

namespace fs = std::filesystem;

std::string findChromium() {
  for (const char* p : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (fs::exists(p)) return p;
  return {};
}

TEST(Browser, HeadlessChromiumShowsTheJobRows) {
  const std::string chromium = findChromium();
  if (chromium.empty()) GTEST_SKIP() << "chromium is not installed (deploy/setup.sh installs it)";
  ASSERT_TRUE(test::scenarioAvailable());
  test::LiveServer live;
  auto client = live.client();
  const std::int64_t jobId = test::submit(*client, Json{{"inputs", test::smallInputs()}, {"name", "browser test"},
                                                        {"sweep", {{"loading.strain_rate", test::twoStrainRates()}}}});
  ASSERT_GT(jobId, 0);
  ASSERT_EQ(test::waitForJob(*client, jobId, {"successful", "failed"}, 180)["status"], "successful");
  test::TempDir profile;
  const fs::path dom = profile.path() / "dom.html";
  for (const std::string& path : {"/jobs/" + std::to_string(jobId) + "?f=html", std::string("/jobs?f=html")}) {
    const std::string url = "http://127.0.0.1:" + std::to_string(live.port()) + path;
    const std::string cmd = "timeout 120 " + chromium + " --headless --no-sandbox --disable-gpu --user-data-dir=" +
                            profile.path().string() + " --virtual-time-budget=3000 --dump-dom '" + url + "' > " +
                            dom.string() + " 2> /dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const std::string text = test::readText(dom);
    if (path.rfind("/jobs?", 0) == 0) {
      EXPECT_NE(text.find("href=\"/jobs/" + std::to_string(jobId) + "?f=html\""), std::string::npos) << text.substr(0, 3000);
      EXPECT_NE(text.find("browser test"), std::string::npos);
      continue;
    }
    EXPECT_NE(text.find("id=\"run-0\""), std::string::npos) << text.substr(0, 3000);
    EXPECT_NE(text.find("id=\"run-1\""), std::string::npos);
    EXPECT_NE(text.find("id=\"summary\""), std::string::npos);
    EXPECT_NE(text.find("<b id=\"status\">successful</b>"), std::string::npos);
  }
}

TEST(Browser, ARunPageShowsItsFieldPicture) {
  // The run page as the browser draws it: its screenshot holds the damage picture's colours
  // (viridis' dark end for the intact elements, the red of the broken bonds), so the <img> loaded.
  const std::string chromium = findChromium();
  if (chromium.empty()) GTEST_SKIP() << "chromium is not installed (deploy/setup.sh installs it)";
  ASSERT_TRUE(test::scenarioAvailable());
  test::LiveServer live;
  auto client = live.client();
  Json inputs = test::smallInputs();
  const std::int64_t jobId = test::submit(*client, Json{{"inputs", inputs}, {"name", "run page"}});
  ASSERT_GT(jobId, 0);
  ASSERT_EQ(test::waitForJob(*client, jobId, {"successful", "failed"}, 180)["status"], "successful");
  test::TempDir profile;
  const fs::path shot = profile.path() / "run.png";
  const std::string url = "http://127.0.0.1:" + std::to_string(live.port()) + "/jobs/" + std::to_string(jobId) +
                          "/runs/0?f=html";
  const std::string cmd = "timeout 120 " + chromium + " --headless --no-sandbox --disable-gpu --user-data-dir=" +
                          profile.path().string() + " --virtual-time-budget=5000 --window-size=1280,1000 --screenshot=" +
                          shot.string() + " '" + url + "' > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const auto png = rupture::testing::probePng(test::readText(shot));
  ASSERT_EQ(png.width, 1280);
  EXPECT_GT(png.near(68, 1, 84, 16), 5000u) << "the damage picture's intact elements are on screen";
}

}  // namespace
}  // namespace rupture::server
