#include "http/request_guard.hpp"

#include <algorithm>
#include <cctype>

#include <arpa/inet.h>

#include "common/utf8.hpp"

namespace rupture::server {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

/// "name:port" / "[v6]:port" / "name" -> the name (lowercase, brackets kept off).
std::string hostName(const std::string& hostHeader) {
  std::string h = lower(hostHeader);
  if (!h.empty() && h.front() == '[') {
    const std::size_t close = h.find(']');
    return close == std::string::npos ? h : h.substr(1, close - 1);
  }
  if (std::count(h.begin(), h.end(), ':') == 1) h = h.substr(0, h.find(':'));
  return h;
}

bool isIpLiteral(const std::string& name) {
  unsigned char buffer[sizeof(in6_addr)];
  return inet_pton(AF_INET, name.c_str(), buffer) == 1 || inet_pton(AF_INET6, name.c_str(), buffer) == 1;
}

bool isMutating(const std::string& method) {
  return method != "GET" && method != "HEAD" && method != "OPTIONS";
}

ApiError queryNotUtf8(const std::string& name) {
  return ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                  "the query parameter '" + toValidUtf8(name) + "' is not valid UTF-8 (after percent-decoding)",
                  toValidUtf8(name), Json{{"in", "query"}});
}

}  // namespace

bool bearerMatches(const std::string& header, const std::string& token) {
  const std::string expected = "Bearer " + token;
  unsigned diff = header.size() != expected.size();
  for (std::size_t i = 0; i < expected.size(); ++i) {
    diff |= static_cast<unsigned char>(i < header.size() ? header[i] : 0) ^ static_cast<unsigned char>(expected[i]);
  }
  return diff == 0;
}

std::optional<ApiError> checkRequest(const httplib::Request& req, const ServerConfig& config) {
  // 1. UTF-8: everything below may be echoed into a JSON document.
  if (!isValidUtf8(req.path)) {
    return ApiError(400, problem::kInvalidRequest, "Bad Request",
                    "the request path is not valid UTF-8 (after percent-decoding)", "path", Json{{"in", "path"}});
  }
  for (const auto& [name, value] : req.params) {
    if (!isValidUtf8(name) || !isValidUtf8(value)) return queryNotUtf8(name);
  }

  // 2. Host (DNS rebinding): a page on a name the attacker controls may resolve to this server, but
  //    its requests carry that name in Host. IP literals cannot be rebound.
  if (req.has_header("Host")) {
    const std::string name = hostName(req.get_header_value("Host"));
    bool known = isIpLiteral(name) || name == "localhost" || name == lower(config.bind);
    for (const std::string& h : config.publicHosts) known = known || name == hostName(h);
    if (!known) {
      return ApiError(421, problem::kMisdirected, "Misdirected Request",
                      "this server does not answer for host '" + toValidUtf8(name) +
                          "'; use its IP address, localhost, or a name listed in --public-host",
                      "Host", Json{{"in", "header"}});
    }
  }

  // 3. Reads too, when the operator asked for it.
  if (!config.readToken.empty() && req.path != "/health") {
    const std::string auth = req.get_header_value("Authorization");
    const bool ok = bearerMatches(auth, config.readToken) || (!config.token.empty() && bearerMatches(auth, config.token));
    if (!ok) {
      return ApiError(401, problem::kUnauthorized, "Unauthorized",
                      auth.empty() ? "this server needs 'Authorization: Bearer <token>' on every request"
                                   : "the bearer token is wrong");
    }
  }

  // 4. Cross-origin writes. Browsers send Origin on cross-origin POST/DELETE; a "simple" request
  //    (text/plain, form types) needs no preflight, so the content type is checked as well.
  if (isMutating(req.method)) {
    if (req.has_header("Origin")) {
      const std::string origin = lower(req.get_header_value("Origin"));
      const std::string host = lower(req.get_header_value("Host"));
      bool allowed = !host.empty() && (origin == "http://" + host || origin == "https://" + host);
      for (const std::string& o : config.allowOrigins) allowed = allowed || origin == lower(o);
      if (!allowed) {
        return ApiError(403, problem::kForbiddenOrigin, "Forbidden",
                        "requests from origin '" + toValidUtf8(req.get_header_value("Origin")) +
                            "' may not change anything here; the operator can allow it with --allow-origin",
                        "Origin", Json{{"in", "header"}});
      }
    }
    if (req.method == "POST") {  // the only method with a body here (PUT and PATCH get 405)
      const std::string type = req.get_header_value("Content-Type");
      std::string media = lower(type.substr(0, type.find(';')));
      media.erase(std::remove_if(media.begin(), media.end(), [](char c) { return c == ' ' || c == '\t'; }), media.end());
      if (media != "application/json") {
        return ApiError(415, problem::kUnsupportedMediaType, "Unsupported Media Type",
                        "the request body must be sent with Content-Type: application/json (got '" +
                            toValidUtf8(type) + "'); with curl use --json",
                        "Content-Type",
                        Json{{"in", "header"}, {"allowed", Json::array({"application/json"})}});
      }
    }
  }
  return std::nullopt;
}

}  // namespace rupture::server
