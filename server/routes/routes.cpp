#include "routes/routes.hpp"

#include <algorithm>
#include <map>
#include <vector>

#include <httplib.h>

#include "common/files.hpp"
#include "common/log.hpp"
#include "common/utf8.hpp"
#include "http/request_guard.hpp"
#include "jobs/job_store.hpp"
#include "routes/answers.hpp"
#include "routes/handlers.hpp"
#include "rupture/spec_error.hpp"

namespace rupture::server {
using httplib::Request;
using httplib::Response;

namespace {

const std::string kId = "([^/]+)";

/// A write the data disk has no room for (the job store's, a file's): nothing was changed, and
/// the same request can succeed once space is freed.
ApiError noRoomToWrite(const Request& req, const std::string& what) {
  logLine("disk full answering " + req.method + " " + toValidUtf8(req.path) + ": " + toValidUtf8(what));
  return ApiError(507, problem::kInsufficientStorage, "Insufficient Storage",
                  "the server's data disk is full: the request was not carried out (nothing was changed); "
                  "retry once space is freed",
                  "", Json{{"retry_after_s", 60}});
}

struct Route {
  const char* method;  // GET, POST or DELETE (HEAD follows GET)
  std::string pattern;  // a regular expression over the whole path
  handlers::Handler handler;
};

/// The API, written once: every other answer (405 with Allow, OPTIONS) is derived from it.
const std::vector<Route>& routeTable() {
  using namespace handlers;
  static const std::vector<Route> table = {
      {"GET", "/", getLanding},
      {"GET", "/health", getHealth},
      {"GET", "/openapi\\.yaml", getOpenApi},
      {"GET", "/api", getOpenApi},
      {"GET", "/conformance", getConformance},
      {"GET", "/processes", getProcesses},
      {"GET", "/processes/" + kId, getProcess},
      {"POST", "/processes/" + kId + "/execution", postExecution},
      {"GET", "/processes/" + kId + "/previews/([0-9a-f]{32})", getProcessPreview},
      {"GET", "/jobs", getJobs},
      {"GET", "/jobs/" + kId, getJob},
      {"DELETE", "/jobs/" + kId, deleteJob},
      {"POST", "/jobs/" + kId + "/retry", postRetry},
      {"POST", "/jobs/" + kId + "/resume", postResume},
      {"GET", "/jobs/" + kId + "/results", getJobResults},
      {"GET", "/jobs/" + kId + "/crate", getJobCrate},
      {"GET", "/jobs/" + kId + "/report", getJobReport},
      {"GET", "/jobs/" + kId + "/runs", getRuns},
      {"GET", "/jobs/" + kId + "/runs/" + kId, getRun},
      {"GET", "/jobs/" + kId + "/runs/" + kId + "/results", getRunResults},
      {"GET", "/jobs/" + kId + "/runs/" + kId + "/series", getRunSeries},
      {"GET", "/jobs/" + kId + "/runs/" + kId + "/field", getRunField},
      {"GET", "/jobs/" + kId + "/runs/" + kId + "/results\\.xdmf", getRunXdmf},
      {"GET", "/jobs/" + kId + "/runs/" + kId + "/bundle", getRunBundle},
      {"GET", "/jobs/" + kId + "/summary", getJobSummary},
      {"GET", "/jobs/" + kId + "/summary\\.svg", getJobSummaryPlot},
      {"GET", "/summary", getComparedSummary},
      {"GET", "/plot", getComparedPlot},
  };
  return table;
}

/// The methods each path answers, in the table's order of first appearance.
std::vector<std::pair<std::string, std::vector<std::string>>> methodsByPath() {
  std::vector<std::pair<std::string, std::vector<std::string>>> paths;
  for (const Route& route : routeTable()) {
    auto it = std::find_if(paths.begin(), paths.end(), [&](const auto& p) { return p.first == route.pattern; });
    if (it == paths.end()) it = paths.insert(paths.end(), {route.pattern, {}});
    it->second.push_back(route.method);
  }
  return paths;
}

}  // namespace

void registerRoutes(HttpFrontend& http, ServerContext& context) {
  // cpp-httplib would apply Range headers to every response, error documents included, and gets
  // ranges past the end wrong: downloads serve them (sendFile), everything else ignores them.
  http.setRequestSetup([](Request& req) { req.ranges.clear(); });
  auto wrap = [&context](handlers::Handler handler) {
    return [&context, handler](const Request& req, Response& res) {
      try {
        handler(context, req, res);
      } catch (const ApiError& e) {
        sendProblem(req, res, e);
      } catch (const rupture::SpecError& e) {
        sendProblem(req, res,
                    ApiError(400, problem::kInvalidSpec, "Invalid spec", e.what(), e.field(),
                             Json{{"value", e.value()}, {"allowed", e.allowed()}}));
      } catch (const nlohmann::json::exception& e) {
        // JSON type and range errors come from what the client sent (the server's own documents
        // are built from checked values).
        sendProblem(req, res, ApiError(400, problem::kInvalidRequest, "Invalid request",
                                       "the request holds a value the server cannot use: " +
                                           truncateUtf8(e.what(), 300)));
      } catch (const std::bad_alloc&) {
        // Not the client's mistake and not a bug: the machine is short of memory right now.
        logLine("out of memory answering " + req.method + " " + toValidUtf8(req.path));
        sendProblem(req, res, ApiError(503, problem::kUnavailable, "Service Unavailable",
                                       "the server could not get the memory this request needs right now; "
                                       "retry later (other requests or runs are using it)",
                                       "", Json{{"retry_after_s", 30}}));
      } catch (const StoreFullError& e) {
        sendProblem(req, res, noRoomToWrite(req, e.what()));
      } catch (const std::exception& e) {
        if (isDiskFull(e.what())) sendProblem(req, res, noRoomToWrite(req, e.what()));
        else sendInternalError(req, res, e.what());
      } catch (...) {
        sendInternalError(req, res, "non-standard exception");
      }
    };
  };

  for (const Route& route : routeTable()) {
    const std::string method = route.method;
    if (method == "GET") http.Get(route.pattern, wrap(route.handler));
    else if (method == "POST") http.Post(route.pattern, httplib::Server::Handler(wrap(route.handler)));
    else if (method == "DELETE") http.Delete(route.pattern, httplib::Server::Handler(wrap(route.handler)));
  }

  // 405 (with Allow) for the other methods on every known path; OPTIONS answers with Allow.
  for (const auto& [pattern, methods] : methodsByPath()) {
    std::string allow;
    for (const auto& m : methods) allow += (allow.empty() ? "" : ", ") + m;
    if (std::find(methods.begin(), methods.end(), "GET") != methods.end()) allow += ", HEAD";
    allow += ", OPTIONS";
    auto notAllowed = [allow](const Request& req, Response& res) {
      res.set_header("Allow", allow);
      sendProblem(req, res,
                  ApiError(405, problem::kMethodNotAllowed, "Method Not Allowed",
                           req.method + " is not allowed on " + req.path + "; allowed: " + allow));
    };
    auto has = [&](const char* m) { return std::find(methods.begin(), methods.end(), m) != methods.end(); };
    if (!has("GET")) http.Get(pattern, notAllowed);
    if (!has("POST")) http.Post(pattern, httplib::Server::Handler(notAllowed));
    if (!has("DELETE")) http.Delete(pattern, httplib::Server::Handler(notAllowed));
    http.Put(pattern, httplib::Server::Handler(notAllowed));
    http.Patch(pattern, httplib::Server::Handler(notAllowed));
    http.Options(pattern, [allow](const Request&, Response& res) {
      res.status = 204;
      res.set_header("Allow", allow);
    });
  }

  // Before the body is read: the request guard (UTF-8, Host, read token, Origin, Content-Type), then
  // bodies without a length: chunked uploads escape cpp-httplib 0.11.4's body-size limit, and a POST
  // without Content-Length has no body by HTTP's framing rules (both 411).
  http.set_pre_routing_handler([&context](const Request& req, Response& res) {
    try {
      if (auto error = checkRequest(req, context.config)) {
        sendProblem(req, res, *error);
        return httplib::Server::HandlerResponse::Handled;
      }
      if (req.has_header("Transfer-Encoding")) {
        res.set_header("Connection", "close");
        sendProblem(req, res, problemForStatus(411));
        return httplib::Server::HandlerResponse::Handled;
      }
      if (req.method == "POST" && !req.has_header("Content-Length")) {
        sendProblem(req, res, problemForStatus(411, "a POST needs a Content-Length header (the body's size in bytes)"));
        return httplib::Server::HandlerResponse::Handled;
      }
    } catch (const std::exception& e) {
      sendInternalError(req, res, e.what());
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });

  // Statuses produced by the HTTP layer itself (404 without a route, 413, 400 bad request line, ...)
  // get a problem document too. Nothing may throw out of here: cpp-httplib calls it outside its
  // try block, and an exception would end the process.
  http.set_error_handler(httplib::Server::HandlerWithResponse([](const Request& req, Response& res) {
    if (!res.body.empty() || res.content_length_ > 0) return httplib::Server::HandlerResponse::Unhandled;
    try {
      sendProblem(req, res, problemForStatus(res.status));
    } catch (const std::exception& e) {
      sendInternalError(req, res, e.what());
    }
    return httplib::Server::HandlerResponse::Handled;
  }));
  http.set_exception_handler([](const Request& req, Response& res, std::exception_ptr ep) {
    std::string what = "unknown exception";
    try {
      if (ep) std::rethrow_exception(ep);
    } catch (const std::bad_alloc&) {
      try {
        sendProblem(req, res, ApiError(503, problem::kUnavailable, "Service Unavailable",
                                       "the server could not get the memory this request needs right now; retry later",
                                       "", Json{{"retry_after_s", 30}}));
        return;
      } catch (...) {
        what = "out of memory";
      }
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    sendInternalError(req, res, what);
  });
  http.set_post_routing_handler([](const Request&, Response& res) {
    res.set_header("X-Content-Type-Options", "nosniff");
    if (!res.has_header("Cache-Control")) res.set_header("Cache-Control", "no-store");
  });
  if (context.config.logRequests) {
    http.set_logger([](const Request& req, const Response& res) {
      logLine(req.remote_addr + " \"" + req.method + " " + req.target + "\" " + std::to_string(res.status));
    });
  }
}


}  // namespace rupture::server
