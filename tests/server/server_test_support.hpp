#pragma once
// Shared helpers for the server tests: temporary data directories, an in-process server on a free
// loopback port, a real HTTP client, JSON helpers and the small dynamic-tension inputs.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include <sys/types.h>

#include <gtest/gtest.h>
#include <httplib.h>

#include "common/problem.hpp"
#include "rupture/run.hpp"
#include "server.hpp"

namespace rupture::server::test {

namespace fs = std::filesystem;

/// A fresh directory under the system temp dir, removed with everything in it at scope exit.
class TempDir {
public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "rupture-server-test-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    m_path = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(m_path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return m_path; }

private:
  fs::path m_path;
};

inline std::string readText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

/// Polls `done` every 20 ms until it is true or `seconds` have passed; returns its last value.
inline bool waitFor(const std::function<bool()>& done, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return done();
}

/// The scenario the end-to-end tests drive.
inline constexpr const char* kScenario = "dynamic-tension";
/// Where jobs of kScenario are submitted.
inline const std::string kExecutePath = std::string("/processes/") + kScenario + "/execution";

/// The server still answers GET /health with 200 (after a request meant to upset it).
inline void expectStillServing(httplib::Client& client) {
  auto res = client.Get("/health");
  ASSERT_TRUE(res) << "the server stopped answering";
  EXPECT_EQ(res->status, 200);
}

inline fs::path exampleFile() { return fs::path(RUPTURE_SOURCE_DIR) / "examples" / "dynamic-tension-small.json"; }

inline bool scenarioAvailable() {
  if (!fs::exists(exampleFile())) return false;
  for (const auto& s : rupture::listScenarios()) {
    if (s.name == kScenario) return true;
  }
  return false;
}

/// The small example's spec without "scenario" (= the POST body's inputs), shrunk further so that a
/// run takes about a second on one core.
Json smallInputs();

/// A swept path that sets how long a run takes, with a value for a quick run (as long as
/// smallInputs()), one for a run of a few seconds, and one for a run that lasts well over ten
/// seconds (to be cancelled).
struct RunLengthKnob {
  std::string path;
  Json quick;
  Json medium;
  Json slow;
};
RunLengthKnob runLengthKnob();

/// Two strain rates for the 2 x 2 grid, a decade apart.
Json twoStrainRates();

/// A real server on 127.0.0.1 with a free port, in this process, with its own data directory.
class LiveServer {
public:
  explicit LiveServer(const std::function<void(ServerConfig&)>& configure = {}, const fs::path& dataDir = {}) {
    ServerConfig config;
    config.port = 0;
    config.bind = "127.0.0.1";
    config.dataDir = dataDir.empty() ? m_dir.path().string() : dataDir.string();
    config.workers = 2;
    config.threadsPerRun = 1;
    config.httpThreads = 8;
    if (configure) configure(config);
    m_server = std::make_unique<RuptureServer>(config);
    m_port = m_server->startInBackground();
  }
  ~LiveServer() { m_server->stop(); }

  int port() const { return m_port; }
  RuptureServer& server() { return *m_server; }
  fs::path dataDir() const { return m_server->config().dataDir; }
  std::unique_ptr<httplib::Client> client() const {
    auto c = std::make_unique<httplib::Client>("127.0.0.1", m_port);
    c->set_read_timeout(30, 0);
    c->set_connection_timeout(5, 0);
    return c;
  }

private:
  TempDir m_dir;
  std::unique_ptr<RuptureServer> m_server;
  int m_port = 0;
};

inline Json parseJson(const std::string& text) { return Json::parse(text); }

/// GET that must answer `status` with a JSON body.
inline Json getJson(httplib::Client& client, const std::string& path, int status = 200) {
  auto res = client.Get(path.c_str());
  if (!res) {
    ADD_FAILURE() << "GET " << path << ": no response (" << httplib::to_string(res.error()) << ")";
    return Json();
  }
  EXPECT_EQ(res->status, status) << "GET " << path << ": " << res->body;
  return Json::parse(res->body);
}

inline httplib::Result postJson(httplib::Client& client, const std::string& path, const Json& body,
                                const httplib::Headers& headers = {}) {
  return client.Post(path.c_str(), headers, body.dump(), "application/json");
}

/// Posts a sweep of `scenario` and returns the job id (the POST must answer 201).
inline std::int64_t submit(httplib::Client& client, const Json& body, const httplib::Headers& headers = {},
                           const std::string& scenario = kScenario) {
  auto res = postJson(client, "/processes/" + scenario + "/execution", body, headers);
  if (!res) {
    ADD_FAILURE() << "POST: no response";
    return -1;
  }
  EXPECT_EQ(res->status, 201) << res->body;
  if (res->status != 201) return -1;
  const Json doc = Json::parse(res->body);
  EXPECT_EQ(res->get_header_value("Location"), "/jobs/" + doc["jobID"].get<std::string>());
  return std::stoll(doc["jobID"].get<std::string>());
}

/// Polls GET /jobs/{id} until its status is one of `statuses`; returns the last document.
inline Json waitForJob(httplib::Client& client, std::int64_t id, const std::set<std::string>& statuses,
                       double seconds) {
  Json doc;
  waitFor(
      [&] {
        auto res = client.Get(("/jobs/" + std::to_string(id)).c_str());
        if (!res || res->status != 200) return false;
        doc = Json::parse(res->body);
        return statuses.count(doc["status"].get<std::string>()) > 0;
      },
      seconds);
  return doc;
}

/// Checks a problem document: status, content type, the RFC 7807 members, and `field` when given.
inline Json expectProblem(const httplib::Result& res, int status, const std::string& field = {}) {
  if (!res) {
    ADD_FAILURE() << "no response";
    return Json();
  }
  EXPECT_EQ(res->status, status) << res->body;
  EXPECT_EQ(res->get_header_value("Content-Type"), kProblemContentType) << res->body;
  Json doc;
  try {
    doc = Json::parse(res->body);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "problem body is not JSON: " << res->body;
    return Json();
  }
  EXPECT_TRUE(doc.contains("type") && doc["type"].is_string()) << res->body;
  EXPECT_TRUE(doc.contains("title") && doc["title"].is_string()) << res->body;
  EXPECT_EQ(doc.value("status", 0), status) << res->body;
  EXPECT_TRUE(doc.contains("detail") && doc["detail"].is_string()) << res->body;
  if (!field.empty()) {
    EXPECT_EQ(doc.value("field", std::string()), field) << res->body;
  }
  return doc;
}

/// rupture-server as a child process on a free loopback port (the first stdout line names it).
class ChildServer {
public:
  ChildServer(const std::filesystem::path& dataDir, const std::vector<std::string>& extra = {});
  ~ChildServer();
  ChildServer(const ChildServer&) = delete;
  ChildServer& operator=(const ChildServer&) = delete;

  int port() const { return m_port; }
  pid_t pid() const { return m_pid; }
  std::unique_ptr<httplib::Client> client() const {
    auto c = std::make_unique<httplib::Client>("127.0.0.1", m_port);
    c->set_read_timeout(30, 0);
    return c;
  }
  /// Sends `signal` and waits up to `seconds` for the exit; returns the exit status
  /// (128 + signal when killed by one) or -1.
  int stop(int signal, double seconds);

private:
  pid_t m_pid = -1;
  int m_stdout = -1;
  int m_port = 0;
};

/// Runs rupture-server with `args` to its end (up to `seconds`, then SIGKILL); returns the exit
/// status and its stderr in `err`.
int runServerToExit(const std::vector<std::string>& args, std::string& err, double seconds = 10);

/// Sends raw bytes to 127.0.0.1:port and returns the server's answer: up to the end of the first
/// response, the connection's close, or `seconds`. For requests a client library would normalise.
std::string rawExchange(int port, const std::string& request, double seconds = 5);

/// The status code of a raw HTTP response ("HTTP/1.1 404 Not Found" -> 404), or -1.
int rawStatus(const std::string& response);

/// The body of a raw (non-chunked) HTTP response.
std::string rawBody(const std::string& response);

/// Minimal XML well-formedness check (tags balance, attributes quoted), enough for our SVG.
bool wellFormedXml(const std::string& text, std::string& error);

/// Splits RFC 4180 CSV into rows of fields.
std::vector<std::vector<std::string>> parseCsv(const std::string& text);

}  // namespace rupture::server::test
