// Issue 55, item 9: every number a person reads on the pages is written by one formatter
// (rupture::formatQuantity): flags as yes/no, an empty cell saying why, an unknown ETA as a word,
// a stage's long decimals rounded, rates alike on both sides of 1e4, wide tables scrolling inside
// the page with a sticky first column; and the pages' live script writes what the server writes.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "rupture/quantity_text.hpp"
#include "support/test_support.hpp"
#include "views/html_page.hpp"
#include "views/html_views.hpp"

namespace rupture::server {
namespace {

using namespace html;

TEST(ReadableNumbers, CellsSayYesNoAndWhyTheyAreEmpty) {
  EXPECT_EQ(cell(Json(true)), "<td>yes</td>");
  EXPECT_EQ(cell(Json(false)), "<td>no</td>");
  EXPECT_EQ(cell(Json(), "run failed"), "<td class=\"none\" title=\"run failed\">—</td>");
  EXPECT_EQ(cell(Json(""), "no name given"), "<td class=\"none\" title=\"no name given\">—</td>");
  const Json separated = {{"name", "separated"}, {"unit", "1"},
                          {"description", "1 when no path of intact bonds joins the two loaded faces any more"}};
  const Json fragments = {{"name", "fragments"}, {"unit", "1"}, {"description", "Macroscopic fragments at the end"}};
  EXPECT_TRUE(isFlag(separated));
  EXPECT_FALSE(isFlag(fragments));
  EXPECT_EQ(quantityCell(Json(1), "1", "", true), "<td title=\"1\">yes</td>");
  EXPECT_EQ(quantityCell(Json(0.0), "1", "", true), "<td title=\"0.0\">no</td>");
  EXPECT_EQ(quantityCell(Json(1.58e-13), "s"), "<td class=\"num\" title=\"1.58e-13\">158 fs</td>");
  EXPECT_EQ(quantityCell(Json(1.35e-15), "J"), "<td class=\"num\" title=\"1.35e-15\">1.35 fJ</td>");
  EXPECT_EQ(whyEmpty(Json{{"status", "failed"}}), "run failed");
  EXPECT_EQ(whyEmpty(Json{{"status", "dismissed"}}), "run cancelled");
  EXPECT_EQ(whyEmpty(Json{{"status", "running"}}), "not finished yet");
  EXPECT_EQ(whyEmpty(Json{{"status", "successful"}}), "not measured by this run");
}

TEST(ReadableNumbers, WideTablesScrollAndTheirCellsReadAlike) {
  // A sweep over 1e4 and 1e5 /s with more results than the headline shows, one run failed.
  Json columns = Json::array({Json{{"name", "loading.strain_rate"}, {"kind", "swept"}, {"unit", "1/s"}, {"label", "Strain rate"}},
                              Json{{"name", "separated"}, {"kind", "result"}, {"unit", "1"}, {"label", "Separated"},
                                   {"description", "1 when no path of intact bonds joins the two loaded faces any more"}}});
  // Named piecewise: GCC 12 misreads "..." + std::string&& (-Wrestrict).
  auto result = [](int k) { return std::string("r").append(std::to_string(k)); };
  for (int k = 0; k < 12; ++k)
    columns.push_back({{"name", result(k)}, {"kind", "result"}, {"unit", "Pa"}, {"label", result(k)}});
  Json ok = {{"run", 0}, {"status", "successful"}, {"loading.strain_rate", 10000.0}, {"separated", 1}};
  for (int k = 0; k < 12; ++k) ok[result(k)] = 58.4e6;
  const Json failed = {{"run", 1}, {"status", "failed"}, {"loading.strain_rate", 1e5}};
  const std::string table = summaryTable(Json{{"columns", columns}, {"rows", {ok, failed}}}, "s");
  EXPECT_NE(table.find("<div class=\"scroll\"><table id=\"s\">"), std::string::npos) << table;
  EXPECT_NE(table.find("<div class=\"scroll\"><table id=\"s-all\">"), std::string::npos) << "All columns scroll too";
  EXPECT_NE(table.find(">1e4 /s</td>"), std::string::npos) << "10000 /s written as 1e5 /s is";
  EXPECT_NE(table.find(">1e5 /s</td>"), std::string::npos);
  EXPECT_EQ(table.find(">10000 /s<"), std::string::npos);
  EXPECT_NE(table.find("<td title=\"1\">yes</td>"), std::string::npos) << "a flag as a word";
  EXPECT_NE(table.find("<td class=\"none\" title=\"run failed\">—</td>"), std::string::npos) << "the failed run's cells say why";
  // The page's style makes the wrapper scroll and its first column stay.
  const std::string style = page("t", table).body;
  EXPECT_NE(style.find(".scroll{overflow-x:auto"), std::string::npos);
  EXPECT_NE(style.find("position:sticky;left:0"), std::string::npos);
}

Json runningJob() {
  return {{"jobID", "9"}, {"processID", "dynamic-tension"}, {"status", "running"}, {"progress", 40},
          {"stage", "main run: peak at 1.1244494114900343 x the plateau"}, {"elapsed_s", 12.3456}, {"eta_s", nullptr},
          {"created", "2026-12-06T00:00:00Z"}, {"updated", "2026-12-06T00:00:12Z"}, {"swept", Json::array()},
          {"runs_by_status", {{"accepted", 0}, {"running", 1}, {"successful", 0}, {"failed", 0}, {"dismissed", 0}}},
          {"runs", Json::array({{{"index", 0}, {"swept", Json::object()}, {"status", "running"}, {"progress", 40},
                                 {"stage", "strain 0.000543219876 of 0.003"}}})}};
}

TEST(ReadableNumbers, TheJobPageWritesTimesAndStagesAsPeopleReadThem) {
  Json status = runningJob();
  std::string page = jobHtml(status, Json(), "").body;
  EXPECT_NE(page.find("<span id=\"eta\" title=\"not enough of the run measured yet to estimate the time left\">unknown</span>"),
            std::string::npos) << page;
  EXPECT_EQ(page.find("</span> s;"), std::string::npos) << "no bare unit after an empty ETA";
  EXPECT_NE(page.find("<span id=\"elapsed\">12.3 s</span>"), std::string::npos);
  EXPECT_NE(page.find("peak at 1.12 x the plateau"), std::string::npos) << "the stage's decimals rounded";
  EXPECT_NE(page.find("strain 5.43e-4 of 0.003"), std::string::npos) << "and the runs'";
  EXPECT_NE(page.find("<div class=\"scroll\"><table id=\"runs\">"), std::string::npos);
  status["eta_s"] = 75.44;
  EXPECT_NE(jobHtml(status, Json(), "").body.find("<span id=\"eta\">75.4 s</span>"), std::string::npos);
  status["status"] = "successful";
  status["eta_s"] = nullptr;
  EXPECT_NE(jobHtml(status, Json(), "").body.find("<span id=\"eta\" title=\"the job has ended\">—</span>"),
            std::string::npos);
}

/// The output of `node file` (empty when node is absent).
std::string runNode(const std::string& script) {
  rupture::testing::ScratchDir dir;
  const std::string path = (dir.path() / "numbers.js").string();
  std::ofstream(path) << script;
  FILE* pipe = ::popen(("node " + path + " 2>&1").c_str(), "r");
  if (!pipe) return {};
  std::string out;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  return ::pclose(pipe) == 0 ? out : std::string();
}

TEST(ReadableNumbers, TheLiveScriptWritesNumbersAsTheServerDoes) {
  if (std::system("node --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "node is not installed";
  const std::vector<std::pair<double, std::string>> quantities = {
      {3.6348609732528563e-09, "s"}, {4.5e-4, "s"}, {1220.708, "s"}, {2e-15, "s"}, {1.58e-13, "s"}, {1e6, "s"},
      {59.96, "s"}, {0.0, "s"}, {0.321, ""}, {3.2e-4, ""}, {21284.0, ""}, {12345.6, ""}, {-1e-7, ""}};
  const std::vector<std::string> texts = {"main run: 1.1244494114900343 x the plateau", "strain 0.000543219876",
                                          "time step 1.5800000000000001e-13 s", "step 14683 of 20000, strain 0.0023",
                                          "run v1.2.3456789 x2.75"};
  std::string script = numberScript() + "\n";
  std::string expected;
  for (const auto& [value, unit] : quantities) {
    script += "console.log(fq(" + Json(value).dump() + ", " + Json(unit).dump() + "));\n";
    expected += rupture::formatQuantity(value, unit) + "\n";
  }
  for (const std::string& text : texts) {
    script += "console.log(r3(" + Json(text).dump() + "));\n";
    expected += rupture::roundNumbersInText(text) + "\n";
  }
  EXPECT_EQ(runNode(script), expected);
}

}  // namespace
}  // namespace rupture::server
