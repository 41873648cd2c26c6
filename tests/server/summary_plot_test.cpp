// Summary tables (JSON, CSV) and the SVG plot: columns, units, log axes, legends, well-formed XML.
#include <gtest/gtest.h>

#include "server_test_support.hpp"
#include "studies/replicate_statistics.hpp"
#include "studies/summary.hpp"
#include "views/plot_png.hpp"
#include "views/svg_plot.hpp"

namespace rupture::server {
namespace {

/// A 3 x 2 grid (strain rate x initial velocity) with one failed run.
std::pair<JobRecord, std::vector<RunRecord>> gridJob() {
  JobRecord job;
  job.id = 7;
  job.processId = "dynamic-tension";
  job.sweptPaths = Json::array({"loading.strain_rate", "loading.initial_velocity"});
  std::vector<RunRecord> runs;
  int k = 0;
  for (double rate : {1e5, 1e6, 1e7}) {
    for (const char* iv : {"V0", "VL"}) {
      RunRecord r;
      r.key = {7, k};
      r.swept = Json::array({rate, iv});
      r.status = Status::Successful;
      r.summary = Json{{"wall_time_s", 1.5}, {"custom", {{"inner", 2}}}, {"peak_stress", 1e8 * (k + 1)},
                       {"fragments", k}};
      if (k == 5) {
        r.status = Status::Failed;
        r.summary = Json();
        r.error = "diverged, \"badly\"";
      }
      runs.push_back(r);
      ++k;
    }
  }
  return {job, runs};
}

PlotRequest plot(const std::string& x, const std::string& y, AxisScale xs = AxisScale::Auto,
                 AxisScale ys = AxisScale::Auto) {
  PlotRequest p;
  p.x = x;
  p.y = y;
  p.xScale = xs;
  p.yScale = ys;
  return p;
}

TEST(Summary, RowsHoldSweptValuesAndScalarsInAStableOrder) {
  auto [job, runs] = gridJob();
  SummaryTable t = buildSummary(job, runs);
  ASSERT_EQ(t.rows.size(), 6u);
  // Declared scalars first, in the scenario's declaration order, then the rest (nested ones flattened).
  ASSERT_GE(t.scalarNames.size(), 4u);
  EXPECT_EQ(t.scalarNames[0], "peak_stress");
  EXPECT_EQ(t.scalarNames[1], "fragments");
  EXPECT_EQ(t.scalarNames[2], "wall_time_s");
  EXPECT_EQ(t.scalarNames[3], "custom.inner");
  Json doc = summaryJson(t);
  EXPECT_EQ(doc["rows"].size(), 6u);
  EXPECT_EQ(doc["rows"][3]["loading.strain_rate"], 1e6);
  EXPECT_EQ(doc["rows"][3]["loading.initial_velocity"], "VL");
  EXPECT_EQ(doc["rows"][3]["peak_stress"], 4e8);
  EXPECT_EQ(doc["rows"][5]["status"], "failed");
  EXPECT_TRUE(doc["rows"][5]["peak_stress"].is_null());
  // Units and labels: swept fields from the schema's "x-unit", scalars from the scenario's declarations.
  EXPECT_EQ(doc["columns"][0]["unit"], "1/s");
  EXPECT_EQ(doc["columns"][1]["unit"], "");  // initial_velocity is text
  // The seed each run used, after the swept values (these runs have no spec: the schema's default).
  EXPECT_EQ(doc["columns"][2]["name"], "sample.seed");
  EXPECT_EQ(doc["columns"][2]["kind"], "input");
  EXPECT_EQ(doc["columns"][2]["unit"], "1");
  EXPECT_EQ(doc["rows"][3]["sample.seed"], 1);
  EXPECT_EQ(doc["columns"][3]["name"], "peak_stress");
  EXPECT_EQ(doc["columns"][3]["unit"], "Pa");
  EXPECT_EQ(doc["columns"][3]["label"], "Peak stress");
  EXPECT_EQ(doc["units"]["peak_stress"], "Pa");
  EXPECT_EQ(doc["units"]["fragments"], "1");
  EXPECT_EQ(doc["units"]["wall_time_s"], "s");
  EXPECT_EQ(doc["units"]["loading.strain_rate"], "1/s");
  EXPECT_EQ(doc["units"]["custom.inner"], "");  // undeclared: no unit invented
}

TEST(Summary, CsvIsRectangularAndQuotesWhatItMust) {
  auto [job, runs] = gridJob();
  const std::string csv = summaryCsv(buildSummary(job, runs));
  auto rows = test::parseCsv(csv);
  ASSERT_EQ(rows.size(), 7u);
  for (const auto& row : rows) EXPECT_EQ(row.size(), rows[0].size());
  EXPECT_EQ(rows[0][0], "run");
  EXPECT_EQ(rows[0][2], "loading.strain_rate [1/s]");
  EXPECT_EQ(rows[0][3], "loading.initial_velocity");
  EXPECT_EQ(rows[0][4], "sample.seed [1]");
  EXPECT_EQ(rows[0][5], "peak_stress [Pa]");
  EXPECT_EQ(rows[0][6], "fragments [1]");
  EXPECT_EQ(rows[0].back(), "error");
  EXPECT_DOUBLE_EQ(std::stod(rows[1][2]), 1e5);
  EXPECT_EQ(rows[1][4], "1");
  EXPECT_DOUBLE_EQ(std::stod(rows[2][5]), 2e8);
  EXPECT_EQ(rows[6].back(), "diverged, \"badly\"");
  EXPECT_EQ(rows[6][5], "");
}

TEST(SvgPlot, LogScaleOnlyWhenValuesSpanDecades) {
  EXPECT_TRUE(prefersLogScale({1e5, 1e6, 1e7}));
  EXPECT_TRUE(prefersLogScale({1e5, 1e6}));
  EXPECT_TRUE(prefersLogScale({1, 2, 5, 10, 20, 50, 100}));
  EXPECT_FALSE(prefersLogScale({1, 2, 3, 4, 5, 6, 7, 8, 9, 10}));
  EXPECT_FALSE(prefersLogScale({1e5, 2e5, 3e5}));
  EXPECT_FALSE(prefersLogScale({-1, 100, 1000}));
  EXPECT_FALSE(prefersLogScale({0, 1e3}));
}

TEST(SvgPlot, PlotHasLogAxisUnitsAndOneSeriesPerOtherSweptValue) {
  auto [job, runs] = gridJob();
  SummaryTable t = buildSummary(job, runs);
  PlotRequest req = plot("loading.strain_rate", "peak_stress");
  const std::string svg = summarySvg(t, req);
  std::string error;
  EXPECT_TRUE(test::wellFormedXml(svg, error)) << error << "\n" << svg;
  EXPECT_NE(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  // Human labels with units; peak stress 1e8..5e8 Pa shown in MPa.
  EXPECT_NE(svg.find(">Strain rate [1/s]</text>"), std::string::npos);
  EXPECT_NE(svg.find(">Peak stress [MPa]</text>"), std::string::npos);
  // Decade ticks 10⁵ .. 10⁷ on the log x axis; plain numbers on the linear y axis.
  for (const char* d : {">10⁵</text>", ">10⁶</text>", ">10⁷</text>"}) EXPECT_NE(svg.find(d), std::string::npos) << d;
  EXPECT_NE(svg.find(">200</text>"), std::string::npos);
  EXPECT_EQ(svg.find("e+"), std::string::npos);
  EXPECT_EQ(svg.find(">2e8<"), std::string::npos);
  // Two series (V0, VL) with a legend titled by the other swept path.
  EXPECT_NE(svg.find("class=\"legend\""), std::string::npos);
  EXPECT_NE(svg.find("data-label=\"V0\""), std::string::npos);
  EXPECT_NE(svg.find("data-label=\"VL\""), std::string::npos);
  std::size_t circles = 0;
  for (std::size_t p = svg.find("<circle cx"); p != std::string::npos; p = svg.find("<circle cx", p + 1)) ++circles;
  EXPECT_EQ(circles, 5u + 2u);  // 5 successful runs + 2 legend markers
}

TEST(SvgPlot, CategoricalXAndLinearY) {
  auto [job, runs] = gridJob();
  SummaryTable t = buildSummary(job, runs);
  PlotRequest req = plot("loading.initial_velocity", "fragments");
  const std::string svg = summarySvg(t, req);
  std::string error;
  EXPECT_TRUE(test::wellFormedXml(svg, error)) << error;
  EXPECT_NE(svg.find(">V0</text>"), std::string::npos);
  EXPECT_NE(svg.find(">Fragments</text>"), std::string::npos);  // dimensionless: no unit brackets
  EXPECT_EQ(svg.find("[-]"), std::string::npos);
  EXPECT_EQ(svg.find("<polyline"), std::string::npos);  // categories are not joined by lines
  EXPECT_NE(svg.find("data-label=\"10⁵ 1/s\""), std::string::npos);  // legend values with their unit
}

TEST(SvgPlot, UnknownColumnsAndImpossibleScalesAre400) {
  auto [job, runs] = gridJob();
  SummaryTable t = buildSummary(job, runs);
  try {
    summarySvg(t, plot("loading.strain_rate", "no_such"));
    FAIL();
  } catch (const ApiError& e) {
    EXPECT_EQ(e.status(), 400);
    EXPECT_EQ(e.field(), "y");
  }
  EXPECT_THROW(summarySvg(t, plot("loading.initial_velocity", "peak_stress", AxisScale::Log)), ApiError);
  PlotRequest linear = plot("loading.strain_rate", "peak_stress", AxisScale::Linear, AxisScale::Log);
  const std::string svg = summarySvg(t, linear);
  EXPECT_NE(svg.find(">Peak stress [Pa]</text>"), std::string::npos);  // log axes keep the SI unit
  EXPECT_NE(svg.find(">10⁸</text>"), std::string::npos);
  PlotRequest empty = plot("loading.strain_rate", "peak_stress");
  empty.yMin = 3e8;
  empty.yMax = 1e8;
  EXPECT_THROW(summarySvg(t, empty), ApiError);
}

TEST(SvgPlot, ErrorBarsFromAPerPointErrorColumn) {
  auto [job, runs] = gridJob();
  // Half-widths on runs 0..3 only; run 4 has none, run 5 failed.
  for (int k = 0; k < 4; ++k) runs[k].summary["peak_stress_ci"] = 0.5e8;
  SummaryTable t = buildSummary(job, runs);
  PlotRequest req = plot("loading.strain_rate", "peak_stress", AxisScale::Auto, AxisScale::Linear);
  req.yError = "peak_stress_ci";
  const std::string svg = summarySvg(t, req);
  std::string error;
  EXPECT_TRUE(test::wellFormedXml(svg, error)) << error;
  std::size_t bars = 0;
  for (std::size_t p = svg.find("class=\"error-bar\""); p != std::string::npos; p = svg.find("class=\"error-bar\"", p + 1)) ++bars;
  EXPECT_EQ(bars, 4u);
  EXPECT_EQ(summarySvg(t, plot("loading.strain_rate", "peak_stress")).find("error-bar"), std::string::npos);
}

TEST(SvgPlot, EngineeringUnitsChosenFromTheData) {
  EXPECT_EQ(displayUnit("Pa", 5.2e7).unit, "MPa");
  EXPECT_DOUBLE_EQ(displayUnit("Pa", 5.2e7).factor, 1e6);
  EXPECT_EQ(displayUnit("Pa", 3e9).unit, "GPa");
  EXPECT_EQ(displayUnit("s", 4e-6).unit, "µs");
  EXPECT_EQ(displayUnit("s", 40).unit, "s");  // no kiloseconds
  EXPECT_EQ(displayUnit("J/m", 2e3).unit, "kJ/m");
  EXPECT_EQ(displayUnit("m^2", 2e-6).unit, "×10⁻⁶ m^2");  // a power has no prefix
  EXPECT_EQ(displayUnit("1/s", 2e5).unit, "×10³ 1/s");
  EXPECT_EQ(displayUnit("1", 2e-3).unit, "×10⁻³");
  EXPECT_EQ(displayUnit("1", 0.4).unit, "");
  EXPECT_EQ(axisTitle("Peak stress", displayUnit("Pa", 5e7)), "Peak stress [MPa]");
}

TEST(SvgPlot, SizeRangeAndLongTitlesFit) {
  auto [job, runs] = gridJob();
  SummaryTable t = buildSummary(job, runs);
  PlotRequest req = plot("loading.strain_rate", "peak_stress", AxisScale::Auto, AxisScale::Linear);
  req.width = 400;
  req.height = 300;
  req.yMin = 0;
  req.yMax = 6e8;
  req.title = std::string(30, 'a') + " " + std::string(30, 'b') + " " + std::string(30, 'c');
  const std::string svg = summarySvg(t, req);
  std::string error;
  EXPECT_TRUE(test::wellFormedXml(svg, error)) << error;
  EXPECT_NE(svg.find("width=\"400\" height=\"300\""), std::string::npos);
  // Range 0..600 MPa: its ends are ticks.
  EXPECT_NE(svg.find(">0</text>"), std::string::npos);
  EXPECT_NE(svg.find(">600</text>"), std::string::npos);
  // 400 px holds about 40 title characters per line: two lines, the second shortened.
  std::size_t lines = 0;
  for (std::size_t p = svg.find("class=\"title\""); p != std::string::npos; p = svg.find("class=\"title\"", p + 1)) ++lines;
  EXPECT_EQ(lines, 2u);
  EXPECT_NE(svg.find("…"), std::string::npos);
}

/// Width and height from a PNG's IHDR chunk (big-endian, bytes 16..23 after the 8-byte signature).
std::pair<std::uint32_t, std::uint32_t> pngSize(const std::string& png) {
  auto u32 = [&](std::size_t at) {
    return (std::uint32_t(std::uint8_t(png[at])) << 24) | (std::uint32_t(std::uint8_t(png[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(png[at + 2])) << 8) | std::uint32_t(std::uint8_t(png[at + 3]));
  };
  return {u32(16), u32(20)};
}

TEST(PlotPng, RendersThePlotAsAPngOfTheAskedSize) {
  auto [job, runs] = gridJob();
  PlotRequest req = plot("loading.strain_rate", "peak_stress");
  req.width = 640;
  req.height = 360;
  const std::string png = renderPng(summarySvg(buildSummary(job, runs), req), 1280, 720);
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(pngSize(png), std::make_pair(std::uint32_t{1280}, std::uint32_t{720}));
  EXPECT_THROW(renderPng("not svg", 10, 10), std::runtime_error);
}

TEST(SvgPlot, EmptyJobStillGivesAValidPlot) {
  auto [job, runs] = gridJob();
  for (auto& r : runs) {
    r.status = Status::Accepted;
    r.summary = Json();
  }
  const std::string svg = summarySvg(buildSummary(job, runs), plot("loading.strain_rate", "peak_stress"));
  std::string error;
  EXPECT_TRUE(test::wellFormedXml(svg, error)) << error;
  EXPECT_NE(svg.find("no finished runs"), std::string::npos);
}

TEST(SvgPlot, LongLegendEntriesWrapAndAMeanSaysHowManyRuns) {
  // A second swept path with long text values: the legend wraps each entry, never cuts it.
  auto [job, runs] = gridJob();
  const std::string longer = "heterogeneous field from a cached preliminary run at 1e5 per second";
  for (auto& r : runs) r.swept[1] = r.swept[1].get<std::string>() + " " + longer;
  const std::string svg = summarySvg(buildSummary(job, runs), plot("loading.strain_rate", "peak_stress"));
  const std::size_t legend = svg.find("class=\"legend\"");
  ASSERT_NE(legend, std::string::npos);
  const std::string part = svg.substr(legend);
  EXPECT_EQ(part.find("…"), std::string::npos) << "a legend entry was cut";
  for (const char* word : {"V0", "VL", "heterogeneous", "preliminary", "second"}) EXPECT_NE(part.find(word), std::string::npos) << word;

  // Three replicates per point: the hover text of a mean says so.
  JobRecord rj;
  rj.id = 9;
  rj.processId = "dynamic-tension";
  rj.sweptPaths = Json::array({"loading.strain_rate"});
  rj.study = Json{{"replicates", {{"count", 3}, {"vary", "sample.seed"}}}};
  std::vector<RunRecord> replicated;
  for (int k = 0; k < 6; ++k) {
    RunRecord r;
    r.key = {9, k};
    r.swept = Json::array({k < 3 ? 1e6 : 1e7});
    r.replicate = k % 3;
    r.status = Status::Successful;
    r.summary = Json{{"peak_stress", 5e7 + 1e6 * k}};
    replicated.push_back(r);
  }
  const SummaryTable table = buildSummary(rj, replicated);
  const SummaryTable means = meansTable(table, aggregateReplicates(table));
  PlotRequest p = plot("loading.strain_rate", "peak_stress");
  p.yError = ciHalfWidthColumn("peak_stress");
  const std::string meanSvg = summarySvg(means, p);
  EXPECT_NE(meanSvg.find("<title>mean of 3 runs: Strain rate 1e6 /s, Peak stress 51 MPa ± "), std::string::npos)
      << meanSvg;
  EXPECT_EQ(meanSvg.find("<title>run "), std::string::npos);
}

}  // namespace
}  // namespace rupture::server
