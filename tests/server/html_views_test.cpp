// HTML views (OGC API style): ?f=html or Accept: text/html gives a server-rendered page with a
// strict CSP and escaped values; JSON stays the default. tests/browser loads the job page in a real
// headless browser.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <limits>

#include "server_test_support.hpp"
#include "views/html_views.hpp"
#include "views/submit_form.hpp"

namespace rupture::server {
namespace {

using test::getJson;
using test::LiveServer;
namespace fs = std::filesystem;

std::string getHtml(httplib::Client& client, const std::string& path, const httplib::Headers& headers = {}) {
  auto res = client.Get(path.c_str(), headers);
  EXPECT_TRUE(res) << path;
  if (!res) return {};
  EXPECT_EQ(res->status, 200) << path << ": " << res->body.substr(0, 300);
  EXPECT_EQ(res->get_header_value("Content-Type"), "text/html; charset=utf-8") << path;
  const std::string csp = res->get_header_value("Content-Security-Policy");
  EXPECT_NE(csp.find("default-src 'none'"), std::string::npos) << csp;
  EXPECT_EQ(csp.find("unsafe-inline"), std::string::npos) << csp;
  EXPECT_EQ(res->body.find("http://"), std::string::npos) << "no external assets: " << path;
  return res->body;
}

class HtmlViews : public ::testing::Test {
protected:
  void SetUp() override {
    if (!test::scenarioAvailable()) GTEST_SKIP();
    client = live.client();
    Json body{{"inputs", test::smallInputs()}, {"name", "html <b>&amp; test</b>"},
              {"sweep", {{"loading.strain_rate", test::twoStrainRates()}}}};
    jobId = test::submit(*client, body);
    ASSERT_GT(jobId, 0);
    ASSERT_EQ(test::waitForJob(*client, jobId, {"successful", "failed"}, 180)["status"], "successful");
  }
  LiveServer live;
  std::unique_ptr<httplib::Client> client;
  std::int64_t jobId = 0;
};

TEST_F(HtmlViews, PagesListTheJobItsRunsSummaryAndPlot) {
  const std::string id = std::to_string(jobId);
  EXPECT_NE(getHtml(*client, "/", {{"Accept", "text/html"}}).find("/processes?f=html"), std::string::npos);
  EXPECT_TRUE(getJson(*client, "/")["links"].is_array()) << "JSON stays the default";
  const std::string processes = getHtml(*client, "/processes?f=html");
  EXPECT_NE(processes.find("loading.strain_rate"), std::string::npos);
  const std::string jobs = getHtml(*client, "/jobs?f=html&name=test&status=successful");
  EXPECT_NE(jobs.find("href=\"/jobs/" + id + "?f=html\""), std::string::npos) << jobs;
  EXPECT_NE(jobs.find("html &lt;b&gt;&amp;amp; test&lt;/b&gt;"), std::string::npos) << "names are escaped";
  EXPECT_EQ(jobs.find("<b>&amp; test</b>"), std::string::npos);
  EXPECT_EQ(getHtml(*client, "/jobs?f=html&name=nothing-like-it").find("href=\"/jobs/" + id + "?f=html\""), std::string::npos);
  EXPECT_EQ(getJson(*client, "/jobs?name=TEST")["numberMatched"], 1);

  const std::string page = getHtml(*client, "/jobs/" + id + "?f=html");
  EXPECT_NE(page.find("id=\"run-0\""), std::string::npos);
  EXPECT_NE(page.find("id=\"run-1\""), std::string::npos);
  EXPECT_NE(page.find("<table id=\"summary\">"), std::string::npos);
  EXPECT_NE(page.find("peak_stress"), std::string::npos);
  EXPECT_NE(page.find("<th title=\"peak_stress\">Peak stress</th>"), std::string::npos) << "the declared label heads it";
  EXPECT_NE(page.find("Pa</td>"), std::string::npos) << "stresses with an engineering prefix: " << page;
  const std::size_t headline = page.find("<table id=\"summary\">"), all = page.find("<table id=\"summary-all\">");
  ASSERT_NE(all, std::string::npos) << "every column one click away";
  const std::string shown = page.substr(headline, page.find("</table>", headline) - headline);
  std::size_t headers = 0;
  for (std::size_t at = shown.find("<th"); at != std::string::npos; at = shown.find("<th", at + 1)) ++headers;
  EXPECT_EQ(headers, 2u + 1u + 8u) << "run, status, the swept rate and eight results: " << shown;
  EXPECT_EQ(shown.find("title=\"bonds\""), std::string::npos) << "a bookkeeping column is not a headline: " << shown;
  EXPECT_NE(page.substr(all).find("title=\"bonds\""), std::string::npos);
  EXPECT_NE(page.find("/summary.svg?x=loading.strain_rate&amp;y=peak_stress"), std::string::npos);
  EXPECT_NE(page.find("/runs/0/bundle"), std::string::npos);
  // What made it, and all of it as an RO-Crate (docs/provenance.md).
  const Json status = getJson(*client, "/jobs/" + id);
  EXPECT_NE(page.find("id=\"provenance\""), std::string::npos);
  EXPECT_NE(page.find("<code>" + status["provenance"]["git_commit"].get<std::string>() + "</code>"), std::string::npos);
  EXPECT_NE(page.find("href=\"/jobs/" + id + "/crate\""), std::string::npos);
  EXPECT_EQ(client->Get(("/jobs/" + id + "?f=xml").c_str())->status, 400);
}

TEST(HtmlJobPage, AFailedJobSaysWhyAndOffersNoFileThatDoesNotExist) {
  const Json status = {
      {"jobID", "7"}, {"processID", "dynamic-tension"}, {"status", "failed"}, {"progress", 12},
      {"message", "1 of 1 run failed"}, {"created", "2026-11-28T00:00:00Z"}, {"updated", "2026-11-28T00:00:01Z"},
      {"swept", Json::array()},
      {"runs_by_status", {{"accepted", 0}, {"running", 0}, {"successful", 0}, {"failed", 1}, {"dismissed", 0}}},
      {"runs", Json::array({{{"index", 0}, {"swept", Json::object()}, {"status", "failed"}, {"progress", 12},
                             {"error", "sample.porosity = <0.9> leaves no path between the faces"}}})}};
  const std::string page = jobHtml(status, Json(), "").body;
  EXPECT_NE(page.find("id=\"reason\">Why: 1 of 1 run failed"), std::string::npos) << page;
  EXPECT_NE(page.find("sample.porosity = &lt;0.9&gt; leaves no path"), std::string::npos) << "the run's reason, escaped";
  EXPECT_EQ(page.find("/runs/0/results"), std::string::npos) << "a failed run has no file to link";
  EXPECT_EQ(page.find("every run in one HDF5 file"), std::string::npos) << "nor the job a merged file";
  EXPECT_NE(page.find("/jobs/7/crate"), std::string::npos) << "an ended job's crate holds its specs and summary";
  Json running = status;
  running["status"] = "running";
  EXPECT_EQ(jobHtml(running, Json(), "").body.find("/crate"), std::string::npos) << "not before its last run (409)";
}

// Issue 55: every scenario's form, submitted as opened, is a job (not a 400 over a default the form
// filled in for a model or shape that was not chosen: bond_gap on a lattice, a crack count on a hole).
TEST(HtmlSubmitForm, EveryScenariosFormAsOpenedIsAValidJob) {
  LiveServer live([](ServerConfig& c) { c.minFreeBytes = std::numeric_limits<long long>::max(); });  // nothing runs
  auto client = live.client();
  const auto scenarios = rupture::listScenarios();
  EXPECT_GE(scenarios.size(), 7u);
  for (const auto& s : scenarios) {
    SCOPED_TRACE(s.name);
    const Json process = getJson(*client, "/processes/" + s.name);
    const Json inputs = formInputs(process, Json::object());
    ASSERT_TRUE(inputs.is_object() && !inputs.empty()) << "the form starts from the schema's example";
    // The page holds what formInputs says it posts: each top-level field's inputs are on it.
    const std::string page = getHtml(*client, "/processes/" + s.name + "?f=html");
    for (const auto& [key, value] : inputs.items())
      EXPECT_NE(page.find("data-path=\"" + key), std::string::npos) << key;
    auto res = test::postJson(*client, "/processes/" + s.name + "/execution", Json{{"inputs", inputs}});
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 201) << inputs.dump() << "\n" << res->body;
  }
  // A default is shown, not sent: impact's example is a square lattice, where bond_gap does not apply.
  const Json impact = getJson(*client, "/processes/impact");
  EXPECT_FALSE(formInputs(impact, Json::object())["sample"].contains("bond_gap"));
  const std::string page = processHtml(impact, Json::object()).body;
  const std::size_t gap = page.find("data-path=\"sample.bond_gap\"");
  ASSERT_NE(gap, std::string::npos);
  const std::string input = page.substr(gap, page.find('>', gap) - gap);
  EXPECT_NE(input.find("value=\"\""), std::string::npos) << input;
  EXPECT_NE(input.find("placeholder=\"default 0.1\""), std::string::npos) << input;
  // A job's variant starts from what that job posted, and posts it back unchanged.
  const Json posted = formInputs(impact, Json::object());
  EXPECT_EQ(formInputs(impact, posted), posted);
}

// Issue 55: Compare pressed with nothing ticked is a page saying what to tick (JSON clients still
// get the problem); the comparison plot claims "mean, 95 % CI" only when a job has replicates.
TEST(HtmlCompare, AnEmptyChoiceIsAPageAndTheTitleClaimsIntervalsOnlyWithReplicates) {
  if (!test::scenarioAvailable()) GTEST_SKIP();
  LiveServer live([](ServerConfig& c) { c.minFreeBytes = std::numeric_limits<long long>::max(); });  // nothing runs
  auto client = live.client();
  for (const auto& [path, headers] : {std::pair<std::string, httplib::Headers>{"/summary?f=html", {}},
                                      {"/summary", {{"Accept", "text/html"}}}}) {
    auto res = client->Get(path.c_str(), headers);
    ASSERT_TRUE(res) << path;
    EXPECT_EQ(res->status, 400) << path;
    EXPECT_EQ(res->get_header_value("Content-Type"), "text/html; charset=utf-8") << path;
    EXPECT_NE(res->body.find("<p id=\"choice\">Nothing to compare: tick the <em>Compare</em> box"), std::string::npos)
        << res->body;
    EXPECT_NE(res->body.find("href=\"/jobs?f=html\""), std::string::npos) << "the way back to the job list";
    EXPECT_EQ(res->body.find("\"type\""), std::string::npos) << "not a problem document: " << res->body;
  }
  test::expectProblem(client->Get("/summary"), 400, "jobs");  // JSON stays a problem document

  const Json sweep = {{"loading.strain_rate", test::twoStrainRates()}};
  const std::int64_t plain = test::submit(*client, {{"inputs", test::smallInputs()}, {"sweep", sweep}});
  const std::int64_t replicated = test::submit(
      *client, {{"inputs", test::smallInputs()}, {"sweep", sweep}, {"replicates", {{"count", 2}, {"vary", "sample.seed"}}}});
  auto title = [&](const std::string& jobs) {
    auto res = client->Get(("/plot?y=peak_stress&jobs=" + jobs).c_str());
    EXPECT_TRUE(res && res->status == 200) << jobs << ": " << (res ? res->body.substr(0, 300) : "no answer");
    return res ? res->body : std::string();
  };
  EXPECT_EQ(title(std::to_string(plain)).find("mean, 95 % CI"), std::string::npos) << "one run per point, no interval";
  EXPECT_NE(title(std::to_string(plain) + "," + std::to_string(replicated)).find("mean, 95 % CI"), std::string::npos);
}

}  // namespace
}  // namespace rupture::server
