// The validation suite over HTTP (docs/validation.md): the validation process runs a sweep over
// cases, its summary is the verdict table, and GET /jobs/{id}/report gives the report as HTML (the
// figures inline), JSON and CSV, with the same verdicts as the runs' summaries; a job of another
// process has no report (404), and a bad format or case gets a 400 naming it.
#include <gtest/gtest.h>

#include "server_test_support.hpp"

namespace rupture::server {
namespace {

using test::expectProblem;
using test::getJson;
using test::LiveServer;

TEST(ValidationReportHttp, ASweepOverCasesReportsTheirVerdictsAsHtmlJsonAndCsv) {
  LiveServer live;
  auto client = live.client();
  expectProblem(test::postJson(*client, "/processes/validation/execution",
                               Json{{"inputs", {{"case", "no-such-case"}, {"level", "quick"}}}}),
                400, "case");
  // The two quickest cases of the quick level (seconds each).
  const Json body = {{"inputs", {{"level", "quick"}}},
                     {"sweep", {{"case", {"lattice-elastic-constants", "piston-column-first-peak"}}}}};
  auto res = test::postJson(*client, "/processes/validation/execution", body);
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 201) << res->body;
  const std::string id = Json::parse(res->body)["jobID"].get<std::string>();
  const Json done = test::waitForJob(*client, std::stoll(id), {"successful", "failed", "dismissed"}, 300);
  ASSERT_EQ(done["status"], "successful") << done.dump();

  const Json summary = getJson(*client, "/jobs/" + id + "/summary");
  ASSERT_EQ(summary["rows"].size(), 2u) << summary.dump().substr(0, 500);
  const Json report = getJson(*client, "/jobs/" + id + "/report?format=json");
  EXPECT_EQ(report["level"], "quick");
  ASSERT_EQ(report["cases"].size(), 2u);
  std::size_t quantities = 0;
  for (const Json& c : report["cases"]) quantities += c["quantities"].size();
  EXPECT_EQ(report["table"].size(), quantities);
  for (const Json& row : summary["rows"]) {  // the swept case and the run's verdict
    bool found = false;
    for (const Json& c : report["cases"])
      if (c["case"] == row["case"]) {
        found = true;
        EXPECT_EQ(c["verdict"], row["verdict"]) << c["case"];
      }
    EXPECT_TRUE(found) << row.dump();
  }
  EXPECT_TRUE(report["not_run"].is_array());  // the cases this job did not sweep

  auto html = client->Get(("/jobs/" + id + "/report").c_str());
  ASSERT_TRUE(html);
  EXPECT_EQ(html->status, 200);
  EXPECT_NE(html->get_header_value("Content-Type").find("text/html"), std::string::npos);
  EXPECT_NE(html->body.find("piston-column-first-peak"), std::string::npos);
  EXPECT_NE(html->body.find("<svg"), std::string::npos);  // the figures inline
  // The headers of every other page (issue 56): a CSP whose nonce admits only the report's own
  // style, no script, and no framing.
  const std::string csp = html->get_header_value("Content-Security-Policy");
  EXPECT_NE(csp.find("default-src 'none'"), std::string::npos) << csp;
  EXPECT_NE(csp.find("frame-ancestors 'none'"), std::string::npos) << csp;
  EXPECT_EQ(html->get_header_value("X-Frame-Options"), "DENY");
  const std::size_t nonceAt = csp.find("style-src 'nonce-");
  ASSERT_NE(nonceAt, std::string::npos) << csp;
  const std::string nonce = csp.substr(nonceAt + 17, csp.find('\'', nonceAt + 17) - nonceAt - 17);
  EXPECT_NE(html->body.find("<style nonce=\"" + nonce + "\">"), std::string::npos);
  EXPECT_EQ(html->body.find("<style>"), std::string::npos);
  EXPECT_EQ(html->body.find("<script"), std::string::npos);
  auto csv = client->Get(("/jobs/" + id + "/report?format=csv").c_str());
  ASSERT_TRUE(csv);
  EXPECT_EQ(csv->status, 200);
  EXPECT_EQ(csv->body.rfind("case,quantity,label,unit,ours,reference", 0), 0u);
  std::size_t lines = 0;
  for (char ch : csv->body) lines += ch == '\n';
  EXPECT_EQ(lines, report["table"].size() + 1);

  expectProblem(client->Get(("/jobs/" + id + "/report?format=pdf").c_str()), 400, "format");

  // The job's page in a browser links the report.
  auto page = client->Get(("/jobs/" + id + "?f=html").c_str());
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("id=\"report\" href=\"/jobs/" + id + "/report\""), std::string::npos);
}

TEST(ValidationReportHttp, AJobOfAnotherProcessHasNoReport) {
  LiveServer live;
  auto client = live.client();
  const Json body = {{"inputs", {{"dimension", 2},
                                 {"geometry", {{"diameter", 0.02}, {"column_height", 0.02}}},
                                 {"resolution", {{"spacing", 0.004}}},
                                 {"run", {{"end_time", 1e-5}}}}}};
  auto res = test::postJson(*client, "/processes/piston-column/execution", body);
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 201) << res->body;
  const std::string id = Json::parse(res->body)["jobID"].get<std::string>();
  test::waitForJob(*client, std::stoll(id), {"successful", "failed", "dismissed"}, 120);
  const Json problem = expectProblem(client->Get(("/jobs/" + id + "/report").c_str()), 404);
  EXPECT_NE(problem.value("detail", std::string()).find("validation"), std::string::npos) << problem.dump();
}

}  // namespace
}  // namespace rupture::server
