// A misspelled key in a submission: 400 naming the unknown key and the nearest allowed one.
#include <gtest/gtest.h>

#include "server_test_support.hpp"

namespace rupture::server {
namespace {

TEST(HelpfulErrors, MisspelledKeyGets400WithDidYouMean) {
  ASSERT_TRUE(test::scenarioAvailable());
  test::LiveServer live;
  auto client = live.client();
  Json inputs = test::smallInputs();
  inputs["loading"]["strain_rte"] = inputs["loading"]["strain_rate"];
  inputs["loading"].erase("strain_rate");
  auto res = test::postJson(*client, std::string("/processes/") + test::kScenario + "/execution", {{"inputs", inputs}});
  const Json doc = test::expectProblem(res, 400, "loading.strain_rte");
  EXPECT_NE(doc.value("detail", "").find("did you mean 'strain_rate'?"), std::string::npos) << doc.dump();
  EXPECT_EQ(doc.value("detail", "").find("(missing)"), std::string::npos) << doc.dump();
  EXPECT_EQ(test::getJson(*client, "/jobs")["numberMatched"], 0) << "no job for a bad submission";
}

}  // namespace
}  // namespace rupture::server
