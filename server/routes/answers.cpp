#include "routes/answers.hpp"

#include <algorithm>
#include <fstream>
#include <memory>

#include "common/files.hpp"
#include "common/log.hpp"
#include "common/public_message.hpp"
#include "common/utf8.hpp"
#include "http/byte_range.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
using httplib::Request;
using httplib::Response;

void sendJson(Response& res, const Json& doc, int status) {
  res.status = status;
  res.set_content(dumpJson(doc), kJsonType);
}

void sendProblem(const Request& req, Response& res, const ApiError& error) {
  res.status = error.status();
  if (error.status() == 401) res.set_header("WWW-Authenticate", "Bearer realm=\"rupture\"");
  // Try-again answers say when: the problem's retry_after_s, else a few seconds.
  if (error.status() == 503 || error.status() == 507) {
    const Json& after = error.extra().contains("retry_after_s") ? error.extra()["retry_after_s"] : Json(5);
    res.set_header("Retry-After", after.is_number_integer() ? after.dump() : "5");
  }
  if (error.status() == 416 && error.extra().contains("size")) {
    res.set_header("Content-Range", "bytes */" + error.extra()["size"].dump());
  }
  res.set_content(dumpJson(problemDocument(error, req.path)), kProblemContentType);
}

/// The last resort for an exception at the HTTP boundary: a 500 problem that names no server
/// detail, and nothing thrown from here (a second failure leaves a bare 500).
void sendInternalError(const Request& req, Response& res, const std::string& what) noexcept {
  try {
    logLine("internal error on " + req.method + " " + toValidUtf8(req.path) + ": " + toValidUtf8(what));
    sendProblem(req, res, ApiError(500, problem::kInternal, "Internal Server Error",
                                   "internal error: " + publicMessage(what)));
  } catch (...) {
    res.status = 500;
    res.body.clear();
  }
}

Json link(const std::string& href, const std::string& rel, const std::string& type,
          const std::string& title) {
  Json l = Json::object();
  l["href"] = href;
  l["rel"] = rel;
  if (!type.empty()) l["type"] = type;
  if (!title.empty()) l["title"] = title;
  return l;
}

void sendHtml(Response& res, const HtmlPage& page) {
  res.set_header("Content-Security-Policy", page.csp());
  res.set_header("X-Frame-Options", "DENY");
  res.set_content(page.body, "text/html; charset=utf-8");
}

/// Streams a file through a content provider (never the whole file in memory), or the one byte
/// range the request asks for (206; 416 past the end).
void sendFile(const Request& req, Response& res, const fs::path& path, const std::string& downloadName) {
  auto size = regularFileSize(path);
  auto stream = std::make_shared<std::ifstream>(path, std::ios::binary);
  if (!size || !*stream) {
    throw ApiError(404, problem::kNoResults, "No results", "the result file is missing on the server");
  }
  const std::uint64_t total = *size;
  const std::optional<ByteRange> range = parseByteRange(req.get_header_value("Range"), total);
  const std::uint64_t first = range ? range->offset : 0;
  const std::uint64_t length = range ? range->length : total;
  res.set_header("Content-Disposition", "attachment; filename=\"" + downloadName + "\"");
  res.set_header("Accept-Ranges", "bytes");
  if (range) {
    res.status = 206;
    res.set_header("Content-Range", "bytes " + std::to_string(first) + "-" + std::to_string(first + length - 1) +
                                        "/" + std::to_string(total));
  }
  res.set_content_provider(
      static_cast<std::size_t>(length), kHdf5Type,
      [stream, first, length](std::size_t offset, std::size_t want, httplib::DataSink& sink) {
        if (offset >= length) return false;
        std::vector<char> buffer(std::min<std::size_t>({want, length - offset, 64 * 1024}));
        stream->clear();
        stream->seekg(static_cast<std::streamoff>(first + offset));
        stream->read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        const std::streamsize n = stream->gcount();
        if (n <= 0) return false;
        return sink.write(buffer.data(), static_cast<std::size_t>(n));
      });
}

}  // namespace rupture::server
