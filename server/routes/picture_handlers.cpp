// The pictures of a run, drawn from its HDF5 file by engine/render: its field at a snapshot
// (GET /jobs/{id}/runs/{k}/field) and its time series (GET .../series?format=svg|png|pdf), each
// behind the render gate and its pixel cap. Every query parameter is honoured or refused with a
// 400 naming it. A picture of a finished run never
// changes while its file does not, so it carries an ETag from the file and the query: a page
// reload costs a 304, not a render.
#include <charconv>
#include <filesystem>
#include <functional>

#include "io/hdf5_file.hpp"
#include "render/field_image.hpp"
#include "render/series_plot.hpp"
#include "routes/handlers.hpp"
#include "routes/request_params.hpp"
#include "views/render_gate.hpp"

namespace rupture::server {

using httplib::Request;
using httplib::Response;
namespace fs = std::filesystem;

namespace {

std::string textParam(const Request& req, const char* name) {
  if (!req.has_param(name)) return "";
  const std::string value = req.get_param_value(name);
  if (value.size() > 64)
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   std::string(name) + " must be at most 64 characters", name, Json{{"in", "query"}});
  return value;
}

render::ImageFormat formatParam(const Request& req) {
  const std::string f = choiceParam(req, "format", {"png", "svg", "pdf"}).value_or("png");
  return f == "svg" ? render::ImageFormat::Svg : f == "pdf" ? render::ImageFormat::Pdf : render::ImageFormat::Png;
}

/// A PNG no larger than --max-render-pixels.
void requirePixels(const Request& req, render::ImageFormat format, int width, int height, long long maxPixels) {
  const long long pixels = static_cast<long long>(width) * height;
  if (format != render::ImageFormat::Png || pixels <= maxPixels) return;
  throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                 "a PNG of " + std::to_string(width) + " x " + std::to_string(height) +
                     " pixels is larger than this server renders (" + std::to_string(maxPixels) +
                     " pixels, --max-render-pixels); lower width or height, or ask for format=svg or pdf",
                 req.has_param("height") ? "height" : "width", Json{{"in", "query"}, {"pixels", pixels}});
}

/// The file's identity and the query: the same picture has the same tag.
std::string entityTag(const fs::path& file, const Request& req) {
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  const auto time = fs::last_write_time(file, ec).time_since_epoch().count();
  std::string key = file.string() + "|" + std::to_string(size) + "|" + std::to_string(time);
  for (const auto& [name, value] : req.params) {
    key += '|';
    key += name;
    key += '=';
    key += value;
  }
  char tag[24] = {'"'};
  const auto [end, _] = std::to_chars(tag + 1, tag + sizeof tag - 1, std::hash<std::string>{}(key), 16);
  *end = '"';
  return std::string(tag, end + 1);
}

/// Answers 304 when the client holds this picture already; otherwise sets the tag and returns false.
bool notModified(const Request& req, Response& res, const std::string& tag) {
  res.set_header("ETag", tag);
  res.set_header("Cache-Control", "private, no-cache");  // revalidate: a retried run rewrites its file
  if (req.get_header_value("If-None-Match") != tag) return false;
  res.status = 304;
  return true;
}

/// A render ends early once the server stops.
render::StopCheck stopCheck(const RenderGate& gate) {
  return [&gate] { return gate.stopRequested(); };
}

[[noreturn]] void badRequest(const render::FieldImageError& e) {
  throw ApiError(400, problem::kInvalidParameter, "Invalid parameter", e.what(), e.member(), Json{{"in", "query"}});
}

}  // namespace

namespace handlers {

void getRunField(ServerContext& ctx, const Request& req, Response& res) {
  refuseUnknownParams(req, {"field", "snapshot", "time", "view", "body", "slice", "bonds", "min", "max", "range",
                            "width", "height", "format", "thumbnail"});
  const JobRecord job = loadJob(ctx, req);
  const RunRecord run = finishedRun(ctx, req, job);
  render::FieldImageRequest r;
  r.field = textParam(req, "field");
  r.view = textParam(req, "view");
  r.body = textParam(req, "body");
  if (req.has_param("bonds")) r.bonds = textParam(req, "bonds");
  if (req.has_param("snapshot")) {
    const std::string text = req.get_param_value("snapshot");
    long value = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || ptr != text.data() + text.size())
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "snapshot must be an integer index (negative counts from the end), got '" + text + "'", "snapshot",
                     Json{{"in", "query"}, {"value", text}});
    r.snapshot = value;
  }
  r.time = numberParam(req, "time");
  r.slice = numberParam(req, "slice");
  r.min = numberParam(req, "min");
  r.max = numberParam(req, "max");
  r.range = choiceParam(req, "range", {"run", "snapshot"}).value_or("run");
  r.thumbnail = choiceParam(req, "thumbnail", {"0", "1"}).value_or("0") == "1";
  r.width = static_cast<int>(intParam(req, "width", r.thumbnail ? 200 : 800, render::kMinImageSide, render::kMaxImageSide));
  r.height = static_cast<int>(intParam(req, "height", r.thumbnail ? 150 : 600, render::kMinImageSide, render::kMaxImageSide));
  r.format = formatParam(req);
  requirePixels(req, r.format, r.width, r.height, ctx.renders->maxPixels());

  const fs::path file = ctx.resultsDir / run.resultPath;
  if (notModified(req, res, entityTag(file, req))) return;
  try {
    // Every picture, thumbnails too (a thumbnail of a large run reads and draws all of it), waits
    // for a render slot.
    const RenderGate::Slot slot = ctx.renders->acquire();
    const render::FieldImage image =
        render::renderFieldImage(io::Hdf5File::openReadOnly(file.string()), r, stopCheck(*ctx.renders));
    res.set_header("X-Field", image.field);
    res.set_header("X-Snapshot", std::to_string(image.snapshot));
    // The colour range drawn and where it came from, so that a client can ask for the same again.
    res.set_header("X-Colour-Range", Json::array({image.min, image.max}).dump());
    res.set_header("X-Colour-Range-Source", image.range);
    res.set_content(image.bytes, image.mediaType);
  } catch (const render::FieldImageError& e) {
    badRequest(e);
  } catch (const render::RenderStopped&) {
    throw RenderGate::stoppingError();
  }
}

void getRunSeriesPlot(ServerContext& ctx, const Request& req, Response& res) {
  refuseUnknownParams(req, {"x", "y", "width", "height", "format"});
  const JobRecord job = loadJob(ctx, req);
  const RunRecord run = finishedRun(ctx, req, job);
  render::SeriesPlotRequest r;
  r.x = textParam(req, "x");
  r.y = paramList(req, "y");
  if (r.y.size() > 8)
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter", "y names at most 8 series", "y",
                   Json{{"in", "query"}});
  r.width = static_cast<int>(intParam(req, "width", 800, render::kMinImageSide, render::kMaxImageSide));
  r.height = static_cast<int>(intParam(req, "height", 500, render::kMinImageSide, render::kMaxImageSide));
  r.format = formatParam(req);
  requirePixels(req, r.format, r.width, r.height, ctx.renders->maxPixels());
  const fs::path file = ctx.resultsDir / run.resultPath;
  if (notModified(req, res, entityTag(file, req))) return;
  try {
    const RenderGate::Slot slot = ctx.renders->acquire();
    const render::SeriesPlot plot =
        render::renderSeriesPlot(io::Hdf5File::openReadOnly(file.string()), r, stopCheck(*ctx.renders));
    res.set_content(plot.bytes, plot.mediaType);
  } catch (const render::FieldImageError& e) {
    badRequest(e);
  } catch (const render::RenderStopped&) {
    throw RenderGate::stoppingError();
  }
}

}  // namespace handlers
}  // namespace rupture::server
