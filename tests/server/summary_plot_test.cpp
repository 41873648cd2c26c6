// Summary tables (JSON, CSV) and the SVG plot: columns, units, log axes, legends, well-formed XML.
#include <gtest/gtest.h>

#include "server_test_support.hpp"
#include "summary.hpp"
#include "svg_plot.hpp"

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

UnitLookup units() {
  return [](const std::string& c) -> std::string {
    if (c == "loading.strain_rate") return "1/s";
    return knownScalarUnit(c);
  };
}

TEST(Summary, RowsHoldSweptValuesAndScalarsInAStableOrder) {
  auto [job, runs] = gridJob();
  SummaryTable t = buildSummary(job, runs);
  ASSERT_EQ(t.rows.size(), 6u);
  // Well-known scalars first, in their canonical order, then the rest (nested ones flattened).
  ASSERT_GE(t.scalarNames.size(), 4u);
  EXPECT_EQ(t.scalarNames[0], "peak_stress");
  EXPECT_EQ(t.scalarNames[1], "fragments");
  EXPECT_EQ(t.scalarNames[2], "wall_time_s");
  EXPECT_EQ(t.scalarNames[3], "custom.inner");
  Json doc = summaryJson(t, units());
  EXPECT_EQ(doc["rows"].size(), 6u);
  EXPECT_EQ(doc["rows"][3]["loading.strain_rate"], 1e6);
  EXPECT_EQ(doc["rows"][3]["loading.initial_velocity"], "VL");
  EXPECT_EQ(doc["rows"][3]["peak_stress"], 4e8);
  EXPECT_EQ(doc["rows"][5]["status"], "failed");
  EXPECT_TRUE(doc["rows"][5]["peak_stress"].is_null());
  EXPECT_EQ(doc["columns"][0]["unit"], "1/s");
  EXPECT_EQ(doc["columns"][2]["name"], "peak_stress");
  EXPECT_EQ(doc["columns"][2]["unit"], "Pa");
}

TEST(Summary, CsvIsRectangularAndQuotesWhatItMust) {
  auto [job, runs] = gridJob();
  const std::string csv = summaryCsv(buildSummary(job, runs));
  auto rows = test::parseCsv(csv);
  ASSERT_EQ(rows.size(), 7u);
  for (const auto& row : rows) EXPECT_EQ(row.size(), rows[0].size());
  EXPECT_EQ(rows[0][0], "run");
  EXPECT_EQ(rows[0][2], "loading.strain_rate");
  EXPECT_EQ(rows[0][4], "peak_stress");
  EXPECT_EQ(rows[0].back(), "error");
  EXPECT_DOUBLE_EQ(std::stod(rows[1][2]), 1e5);
  EXPECT_DOUBLE_EQ(std::stod(rows[2][4]), 2e8);
  EXPECT_EQ(rows[6].back(), "diverged, \"badly\"");
  EXPECT_EQ(rows[6][4], "");
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
  const std::string svg = summarySvg(t, req, units());
  std::string error;
  EXPECT_TRUE(test::wellFormedXml(svg, error)) << error << "\n" << svg;
  EXPECT_NE(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_NE(svg.find("loading.strain_rate [1/s] (log scale)"), std::string::npos);
  EXPECT_NE(svg.find("peak_stress [Pa]"), std::string::npos);
  // Decade ticks 10^5 .. 10^7.
  for (const char* d : {">5</tspan>", ">6</tspan>", ">7</tspan>"}) EXPECT_NE(svg.find(d), std::string::npos) << d;
  EXPECT_NE(svg.find(">2e8</text>"), std::string::npos);  // compact tick labels on the linear y axis
  EXPECT_EQ(svg.find("e+0"), std::string::npos);
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
  const std::string svg = summarySvg(t, req, units());
  std::string error;
  EXPECT_TRUE(test::wellFormedXml(svg, error)) << error;
  EXPECT_EQ(svg.find("(log scale)"), std::string::npos);
  EXPECT_NE(svg.find(">V0</text>"), std::string::npos);
  EXPECT_NE(svg.find("fragments [-]"), std::string::npos);
}

TEST(SvgPlot, UnknownColumnsAndImpossibleScalesAre400) {
  auto [job, runs] = gridJob();
  SummaryTable t = buildSummary(job, runs);
  try {
    summarySvg(t, plot("loading.strain_rate", "no_such"), units());
    FAIL();
  } catch (const ApiError& e) {
    EXPECT_EQ(e.status(), 400);
    EXPECT_EQ(e.field(), "y");
  }
  EXPECT_THROW(summarySvg(t, plot("loading.initial_velocity", "peak_stress", AxisScale::Log), units()), ApiError);
  PlotRequest linear = plot("loading.strain_rate", "peak_stress", AxisScale::Linear, AxisScale::Log);
  const std::string svg = summarySvg(t, linear, units());
  EXPECT_NE(svg.find("peak_stress [Pa] (log scale)"), std::string::npos);
}

TEST(SvgPlot, EmptyJobStillGivesAValidPlot) {
  auto [job, runs] = gridJob();
  for (auto& r : runs) {
    r.status = Status::Accepted;
    r.summary = Json();
  }
  const std::string svg = summarySvg(buildSummary(job, runs), plot("loading.strain_rate", "peak_stress"), units());
  std::string error;
  EXPECT_TRUE(test::wellFormedXml(svg, error)) << error;
  EXPECT_NE(svg.find("no finished runs"), std::string::npos);
}

}  // namespace
}  // namespace rupture::server
