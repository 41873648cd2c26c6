#pragma once
// Client-facing errors as RFC 7807 problem documents (application/problem+json).
// Handlers throw ApiError; the router turns it into the response. Every problem names its `type`
// (a URI), `title`, `status`, `detail`, and, where a field is at fault, its dotted path in `field`.
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace rupture::server {

using Json = nlohmann::ordered_json;

/// Problem type URIs. The OGC API - Processes ones are used where the standard defines them.
namespace problem {
inline constexpr const char* kNoSuchProcess =
    "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/no-such-process";
inline constexpr const char* kNoSuchJob =
    "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/no-such-job";
inline constexpr const char* kResultNotReady =
    "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/result-not-ready";
inline constexpr const char* kInvalidJson = "urn:rupture:problem:invalid-json";
inline constexpr const char* kInvalidRequest = "urn:rupture:problem:invalid-request";
inline constexpr const char* kInvalidSpec = "urn:rupture:problem:invalid-spec";
inline constexpr const char* kInvalidSweep = "urn:rupture:problem:invalid-sweep";
inline constexpr const char* kTooManyRuns = "urn:rupture:problem:too-many-runs";
inline constexpr const char* kInvalidParameter = "urn:rupture:problem:invalid-parameter";
inline constexpr const char* kNotFound = "urn:rupture:problem:not-found";
inline constexpr const char* kNoResults = "urn:rupture:problem:no-results";
inline constexpr const char* kCrateTooLarge = "urn:rupture:problem:crate-too-large";
inline constexpr const char* kNothingToRetry = "urn:rupture:problem:nothing-to-retry";
inline constexpr const char* kUnauthorized = "urn:rupture:problem:unauthorized";
inline constexpr const char* kMethodNotAllowed = "urn:rupture:problem:method-not-allowed";
inline constexpr const char* kPayloadTooLarge = "urn:rupture:problem:payload-too-large";
inline constexpr const char* kLengthRequired = "urn:rupture:problem:length-required";
inline constexpr const char* kRangeNotSatisfiable = "urn:rupture:problem:range-not-satisfiable";
inline constexpr const char* kShuttingDown = "urn:rupture:problem:shutting-down";
inline constexpr const char* kRequestTimeout = "urn:rupture:problem:request-timeout";
inline constexpr const char* kHeadersTooLarge = "urn:rupture:problem:headers-too-large";
inline constexpr const char* kMisdirected = "urn:rupture:problem:misdirected-request";
inline constexpr const char* kForbiddenOrigin = "urn:rupture:problem:forbidden-origin";
inline constexpr const char* kUnsupportedMediaType = "urn:rupture:problem:unsupported-media-type";
inline constexpr const char* kIdempotencyKeyReused = "urn:rupture:problem:idempotency-key-reused";
inline constexpr const char* kUnavailable = "urn:rupture:problem:unavailable";
inline constexpr const char* kInsufficientStorage = "urn:rupture:problem:insufficient-storage";
inline constexpr const char* kQueueFull = "urn:rupture:problem:queue-full";
inline constexpr const char* kInternal = "urn:rupture:problem:internal-error";
}  // namespace problem

/// An error the client should see. `extra` members are merged into the problem document.
class ApiError : public std::runtime_error {
public:
  ApiError(int status, std::string type, std::string title, std::string detail,
           std::string field = {}, Json extra = Json::object())
      : std::runtime_error(detail), m_status(status), m_type(std::move(type)),
        m_title(std::move(title)), m_field(std::move(field)), m_extra(std::move(extra)) {}

  int status() const { return m_status; }
  const std::string& type() const { return m_type; }
  const std::string& title() const { return m_title; }
  const std::string& field() const { return m_field; }
  const Json& extra() const { return m_extra; }

private:
  int m_status;
  std::string m_type, m_title, m_field;
  Json m_extra;
};

/// A response body: indented JSON and a newline. Never throws on bytes that are not UTF-8 (a path
/// or query value echoed into a message): they become U+FFFD, so every body is valid UTF-8.
std::string dumpJson(const Json& doc);

/// The problem document of an error (`instance` is the request path when given).
Json problemDocument(const ApiError& error, const std::string& instance = {});

/// A default problem document for a bare status code (404 route, 413 from the HTTP layer, ...).
ApiError problemForStatus(int status, const std::string& detail = {});

/// Reason phrase for a status code ("Not Found").
const char* statusTitle(int status);

inline constexpr const char* kProblemContentType = "application/problem+json";

}  // namespace rupture::server
