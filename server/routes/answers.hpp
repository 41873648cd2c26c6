#pragma once
// How handlers answer: JSON documents, problem documents (RFC 9457), HTML pages, links and
// streamed files with byte ranges.
#include <filesystem>
#include <string>

#include <httplib.h>

#include "common/problem.hpp"
#include "views/html_views.hpp"

namespace rupture::server {

inline constexpr const char* kJsonType = "application/json";
inline constexpr const char* kHdf5Type = "application/x-hdf5";
inline constexpr const char* kCsvType = "text/csv; charset=utf-8";
inline constexpr const char* kOgcRel = "http://www.opengis.net/def/rel/ogc/1.0/";

void sendJson(httplib::Response& res, const Json& doc, int status = 200);

/// The problem document, with the headers its status implies (Retry-After, WWW-Authenticate,
/// Content-Range).
void sendProblem(const httplib::Request& req, httplib::Response& res, const ApiError& error);

/// The last resort for an exception at the HTTP boundary: a 500 problem that names no server
/// detail, and nothing thrown from here (a second failure leaves a bare 500).
void sendInternalError(const httplib::Request& req, httplib::Response& res, const std::string& what) noexcept;

void sendHtml(httplib::Response& res, const HtmlPage& page);

/// Streams a file through a content provider (never the whole file in memory), or the one byte
/// range the request asks for (206; 416 past the end).
void sendFile(const httplib::Request& req, httplib::Response& res, const std::filesystem::path& path,
              const std::string& downloadName);

/// A link object of OGC API documents.
Json link(const std::string& href, const std::string& rel, const std::string& type = kJsonType,
          const std::string& title = {});

}  // namespace rupture::server
