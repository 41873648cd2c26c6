// Summaries and plots: one job's table (JSON, CSV, replicate statistics, rate dependence) and
// plot, and the comparison of several jobs.
#include <algorithm>

#include <httplib.h>

#include "routes/answers.hpp"
#include "routes/handlers.hpp"
#include "routes/request_params.hpp"
#include "studies/job_comparison.hpp"
#include "studies/rate_dependence.hpp"
#include "studies/replicate_statistics.hpp"
#include "studies/summary.hpp"
#include "views/html_views.hpp"
#include "views/plot_png.hpp"
#include "views/render_gate.hpp"
#include "views/svg_plot.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
using httplib::Request;
using httplib::Response;

namespace {

/// The jobs of ?jobs=3,5,7 with their summary tables: 400 when the list is missing, malformed,
/// repeats a job or is longer than kMaxComparedJobs; 404 naming the first unknown job.
std::vector<ComparedJob> loadComparedJobs(ServerContext& ctx, const Request& req) {
  const std::vector<std::string> ids = paramList(req, "jobs");
  if (ids.empty()) {
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   "jobs is required: a comma-separated list of job ids, e.g. ?jobs=3,5", "jobs", Json{{"in", "query"}});
  }
  if (ids.size() > kMaxComparedJobs) {
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   "jobs lists " + std::to_string(ids.size()) + " jobs; at most " + std::to_string(kMaxComparedJobs) +
                       " can be compared at once",
                   "jobs", Json{{"in", "query"}, {"value", ids.size()}, {"maximum", kMaxComparedJobs}});
  }
  std::vector<ComparedJob> jobs;
  for (const std::string& text : ids) {
    auto id = parseIndex(text);
    if (!id || *id < 1) {
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "jobs holds '" + text + "', which is not a job id (a positive integer)", "jobs",
                     Json{{"in", "query"}, {"value", text}});
    }
    for (const ComparedJob& j : jobs) {
      if (j.job.id == *id) {
        throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                       "jobs lists job " + text + " twice", "jobs", Json{{"in", "query"}, {"value", text}});
      }
    }
    auto job = ctx.store->jobWithRuns(*id);
    if (!job) {
      throw ApiError(404, problem::kNoSuchJob, "No such job",
                     "no job '" + text + "' (named in the jobs list; GET /jobs lists them)", "jobs",
                     Json{{"in", "query"}, {"value", text}});
    }
    jobs.push_back({job->job, buildSummary(job->job, job->runs)});
  }
  return jobs;
}

std::string columnLabel(const SummaryTable& table, const std::string& column) {
  return table.hasColumn(column) ? table.columnInfo(column).label : column;
}

/// The plot query options shared by summary.svg and /plot: xscale, yscale, width, height, ymin,
/// ymax and yerror (a column of `table` holding each point's error half-width).
void readPlotOptions(const Request& req, const SummaryTable& table, PlotRequest& plot) {
  // Every option is honoured or refused: a parameter a plot does not know (a typo) is a
  // 400 naming it, never silently ignored.
  static const std::vector<std::string> known = {"x",     "y",      "xscale", "yscale", "width",    "height", "ymin",
                                                 "ymax",  "yerror", "title",  "format", "scale",    "jobs",   "fontsize"};
  refuseUnknownParams(req, known);
  if (req.has_param("title")) {
    plot.title = req.get_param_value("title");
    if (plot.title.size() > 300) {
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "title must be at most 300 bytes, got " + std::to_string(plot.title.size()), "title",
                     Json{{"in", "query"}});
    }
  }
  plot.xScale = scaleParam(req, "xscale");
  plot.yScale = scaleParam(req, "yscale");
  plot.width = static_cast<int>(intParam(req, "width", 800, kMinWidth, kMaxWidth));
  plot.height = static_cast<int>(intParam(req, "height", 500, kMinHeight, kMaxHeight));
  plot.fontSize = static_cast<int>(intParam(req, "fontsize", 12, kMinFontSize, kMaxFontSize));
  plot.yMin = numberParam(req, "ymin");
  plot.yMax = numberParam(req, "ymax");
  if (req.has_param("yerror")) plot.yError = req.get_param_value("yerror");
  if (!plot.yError.empty() && !table.hasColumn(plot.yError)) {
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   "yerror='" + plot.yError + "' is not a column of this summary", "yerror",
                   Json{{"in", "query"}, {"value", plot.yError}});
  }
}

/// A PNG of width x height x scale² pixels at most the cap (--max-render-pixels): the
/// parameter that makes it larger is named.
void requireRenderable(const PlotRequest& plot, int scale, long long maxPixels) {
  const long long pixels = static_cast<long long>(plot.width) * plot.height * scale * scale;
  if (pixels <= maxPixels) return;
  const char* field = scale > 1 ? "scale" : "width";
  throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                 "a PNG of " + std::to_string(plot.width * scale) + " x " + std::to_string(plot.height * scale) +
                     " pixels (width x height x scale) is larger than this server renders (" +
                     std::to_string(maxPixels) + " pixels, --max-render-pixels); lower " + field +
                     ", or ask for SVG (format=svg), which has no size limit",
                 field, Json{{"in", "query"}, {"pixels", pixels}, {"max_pixels", maxPixels}});
}

/// The plot as SVG, with ?format=png&scale=1..4 as PNG, or with ?format=pdf as a vector PDF.
void sendPlot(const Request& req, Response& res, const SummaryTable& table, const PlotRequest& plot,
                     RenderGate& gate) {
  const std::string format = choiceParam(req, "format", {"svg", "png", "pdf"}).value_or("svg");
  const int scale = static_cast<int>(intParam(req, "scale", 1, 1, 4));
  if (format == "png") requireRenderable(plot, scale, gate.maxPixels());
  const std::string svg = rupture::server::summarySvg(table, plot);
  const render::StopCheck stop = [&gate] { return gate.stopRequested(); };
  try {
    if (format == "png") {
      const RenderGate::Slot slot = gate.acquire();
      res.set_content(renderPng(svg, plot.width * scale, plot.height * scale, stop), "image/png");
    } else if (format == "pdf") {
      const RenderGate::Slot slot = gate.acquire();
      res.set_content(renderPdf(svg, plot.width, plot.height, stop), "application/pdf");
    } else {
      res.set_content(svg, "image/svg+xml");
    }
  } catch (const render::RenderStopped&) {
    throw RenderGate::stoppingError();
  }
}

}  // namespace

namespace handlers {

void getJobSummary(ServerContext& ctx, const Request& req, Response& res) {
  const auto [job, runs] = loadJobWithRuns(ctx, req);
  const SummaryTable table = buildSummary(job, runs);
  const bool aggregate = aggregateParam(req);
  const bool csv = wantsCsv(req);
  if (csv) {
    res.set_content(aggregate ? aggregateCsv(table, aggregateReplicates(table)) : summaryCsv(table), kCsvType);
    return;
  }
  const std::vector<PointAggregate> points = aggregateReplicates(table);
  Json doc = aggregate ? aggregateJson(table, points) : summaryJson(table);
  doc["status"] = toString(job.status);
  if (Json rates = rateDependence(table, points); !rates.is_null()) doc["rate_dependence"] = rates;
  sendJson(res, doc);
}

/// GET /summary?jobs=3,5,7: the rows (or, with aggregate=replicates, the points) of several jobs.
void getComparedSummary(ServerContext& ctx, const Request& req, Response& res) {
  std::vector<ComparedJob> jobs;
  try {
    jobs = loadComparedJobs(ctx, req);
  } catch (const ApiError& e) {
    // Compare pressed with nothing (or too much) ticked: a page saying what to tick, not a problem
    // document in the browser. Clients asking for JSON or CSV still get the problem.
    if (!wantsHtml(req) || e.field() != "jobs") throw;
    res.status = e.status();
    return sendHtml(res, compareChoiceHtml(e.what(), kMaxComparedJobs));
  }
  const bool aggregate = aggregateParam(req);
  if (wantsHtml(req)) {
    std::string ids;
    for (const ComparedJob& j : jobs) {
      if (!ids.empty()) ids += ',';
      ids += std::to_string(j.job.id);
    }
    // The plot needs a swept x; jobs that sweep nothing get the table alone.
    const SummaryTable plotTable = comparisonPlotTable(jobs);
    const std::string plot = plotTable.sweptPaths.size() > 1 ? "/plot?jobs=" + ids : "";
    return sendHtml(res, comparisonHtml(comparisonJson(jobs, aggregate), plot));
  }
  if (wantsCsv(req)) {
    res.set_content(comparisonCsv(jobs, aggregate), kCsvType);
    return;
  }
  sendJson(res, comparisonJson(jobs, aggregate));
}

/// GET /plot?jobs=3,5,7: one series per job (point means, 95 % intervals as error bars).
void getComparedPlot(ServerContext& ctx, const Request& req, Response& res) {
  const std::vector<ComparedJob> jobs = loadComparedJobs(ctx, req);
  const SummaryTable table = comparisonPlotTable(jobs);
  PlotRequest plot;
  plot.x = req.has_param("x") ? req.get_param_value("x") : (table.sweptPaths.size() > 1 ? table.sweptPaths[1] : "");
  plot.y = req.has_param("y") ? req.get_param_value("y") : table.headlineQuantity();
  if (plot.x.empty()) {
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   "these jobs sweep nothing; name the x column with ?x=", "x", Json{{"in", "query"}});
  }
  // Each point is a mean: its 95 % interval is the error bar unless ?yerror= names another column.
  if (table.hasColumn(ciHalfWidthColumn(plot.y))) plot.yError = ciHalfWidthColumn(plot.y);
  readPlotOptions(req, table, plot);
  std::string ids;
  for (const ComparedJob& j : jobs) ids += (ids.empty() ? "" : ", ") + std::to_string(j.job.id);
  // Means with 95 % intervals only where some job has replicates; otherwise each point is one run.
  const bool replicated = std::any_of(jobs.begin(), jobs.end(), [](const ComparedJob& j) { return j.table.replicated; });
  if (plot.title.empty())
    plot.title = columnLabel(table, plot.y) + " vs " + columnLabel(table, plot.x) + " - jobs " + ids +
                 (replicated ? " - mean, 95 % CI" : "");
  sendPlot(req, res, table, plot, *ctx.renders);
}

void getJobSummaryPlot(ServerContext& ctx, const Request& req, Response& res) {
  const auto [job, runs] = loadJobWithRuns(ctx, req);
  SummaryTable table = buildSummary(job, runs);
  PlotRequest plot;
  plot.x = req.has_param("x") ? req.get_param_value("x")
                              : (table.sweptPaths.empty() ? std::string() : table.sweptPaths.front());
  plot.y = req.has_param("y") ? req.get_param_value("y") : table.headlineQuantity();
  if (plot.x.empty()) {
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   "this job sweeps nothing; name the x column with ?x=", "x", Json{{"in", "query"}});
  }
  const bool replicated = table.replicated && table.hasColumn(plot.y);
  if (replicated) {
    // Replicates: one point per sweep point, at the mean, with its 95 % interval as the error bar
    // (unless ?yerror= names another column, e.g. peak_stress.sd).
    table = meansTable(table, aggregateReplicates(table));
    if (table.hasColumn(ciHalfWidthColumn(plot.y))) plot.yError = ciHalfWidthColumn(plot.y);
  }
  readPlotOptions(req, table, plot);
  if (plot.title.empty()) {
    plot.title = columnLabel(table, plot.y) + " vs " + columnLabel(table, plot.x) + " - job " +
                 std::to_string(job.id) + (job.name.empty() ? "" : " (" + job.name + ")") +
                 (replicated ? " - mean, 95 % CI" : "");
  }
  sendPlot(req, res, table, plot, *ctx.renders);
}

}  // namespace handlers

}  // namespace rupture::server
