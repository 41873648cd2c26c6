// Crash safety with the real rupture-server binary: SIGKILL mid-sweep, restart on the same data
// directory, every run finishes, and runs finished before the kill are byte-identical afterwards.
// Also: SIGTERM stops it gracefully (exit 0) and the interrupted run is re-queued.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <map>

#include <gtest/gtest.h>

#include "server_test_support.hpp"

namespace rupture::server {
namespace {

using test::getJson;

/// rupture-server as a child process on a free loopback port.
class ChildServer {
public:
  ChildServer(const std::filesystem::path& dataDir, const std::vector<std::string>& extra = {}) {
    int out[2];
    if (pipe(out) != 0) throw std::runtime_error("pipe failed");
    std::vector<std::string> args = {RUPTURE_SERVER, "--port", "0", "--bind", "127.0.0.1",
                                     "--data-dir", dataDir.string(), "--workers", "1", "--threads-per-run", "1"};
    args.insert(args.end(), extra.begin(), extra.end());
    m_pid = fork();
    if (m_pid == 0) {
      dup2(out[1], STDOUT_FILENO);
      close(out[0]);
      close(out[1]);
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(argv[0], argv.data());
      _exit(127);
    }
    close(out[1]);
    m_stdout = out[0];
    // First stdout line: "rupture-server listening on http://127.0.0.1:<port>".
    std::string line;
    char c;
    while (read(m_stdout, &c, 1) == 1 && c != '\n') line += c;
    const auto colon = line.rfind(':');
    if (line.find("listening on") == std::string::npos || colon == std::string::npos) {
      throw std::runtime_error("rupture-server did not start: '" + line + "'");
    }
    m_port = std::stoi(line.substr(colon + 1));
  }
  ~ChildServer() {
    if (m_pid > 0) {
      kill(m_pid, SIGKILL);
      waitpid(m_pid, nullptr, 0);
    }
    if (m_stdout >= 0) close(m_stdout);
  }

  int port() const { return m_port; }
  std::unique_ptr<httplib::Client> client() const {
    auto c = std::make_unique<httplib::Client>("127.0.0.1", m_port);
    c->set_read_timeout(30, 0);
    return c;
  }
  /// Sends `signal` and waits up to `seconds` for the exit; returns the exit status or -1.
  int stop(int signal, double seconds) {
    kill(m_pid, signal);
    int status = 0;
    const bool exited = test::waitFor([&] { return waitpid(m_pid, &status, WNOHANG) == m_pid; }, seconds);
    if (!exited) return -1;
    m_pid = -1;
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
    return -1;
  }

private:
  pid_t m_pid = -1;
  int m_stdout = -1;
  int m_port = 0;
};

std::map<int, std::string> downloadFinishedRuns(httplib::Client& client, const std::string& job, const Json& doc) {
  std::map<int, std::string> out;
  for (const auto& run : doc["runs"]) {
    if (run["status"] != "successful") continue;
    const int k = run["index"];
    auto res = client.Get((job + "/runs/" + std::to_string(k) + "/results").c_str());
    EXPECT_TRUE(res && res->status == 200);
    if (res) out[k] = res->body;
  }
  return out;
}

/// Polls the job until `done(doc)`; returns whether it happened, leaving the last document in doc.
bool waitForDoc(httplib::Client& client, const std::string& job, Json& doc, const std::function<bool(const Json&)>& done,
                double seconds) {
  return test::waitFor([&] {
    auto res = client.Get(job.c_str());
    if (!res || res->status != 200) return false;
    doc = Json::parse(res->body);
    return done(doc);
  }, seconds);
}

TEST(CrashRecovery, KilledMidSweepRestartsFinishesEveryRunAndNeverRecomputes) {
  ASSERT_TRUE(test::scenarioAvailable()) << "the dynamic-tension scenario or its small example is missing";
  test::TempDir data;
  const auto knob = test::runLengthKnob();
  // Four runs on one worker, one after the other; the last two last a few seconds, so that the
  // kill and the stop land while one runs.
  Json body = {{"inputs", test::smallInputs()},
               {"sweep", {{knob.path, {knob.quick, knob.quick, knob.medium, knob.medium}}}},
               {"sweep_mode", "zip"}};
  std::string job;
  std::int64_t id = 0;
  std::map<int, std::string> before;
  std::map<int, std::filesystem::file_time_type> mtimes;
  auto runFile = [&](int k) {
    return data.path() / "jobs" / std::to_string(id) / ("run-" + std::to_string(k) + ".h5");
  };

  // 1. SIGKILL while run 2 runs, after runs 0 and 1 finished.
  {
    ChildServer server(data.path());
    auto client = server.client();
    id = test::submit(*client, body);
    job = "/jobs/" + std::to_string(id);
    Json doc;
    ASSERT_TRUE(waitForDoc(*client, job, doc, [](const Json& d) {
      return d["runs"][1]["status"] == "successful" && d["runs"][2]["status"] == "running";
    }, 120)) << doc.dump(2);
    before = downloadFinishedRuns(*client, job, doc);
    ASSERT_EQ(before.size(), 2u);
    for (const auto& [k, bytes] : before) {
      EXPECT_EQ(test::readText(runFile(k)), bytes);
      mtimes[k] = std::filesystem::last_write_time(runFile(k));
    }
    EXPECT_EQ(server.stop(SIGKILL, 5), 128 + SIGKILL);
  }

  // 2. Restart: finished runs are kept as they are, the killed run starts again. Then SIGTERM while
  //    a run is running: a graceful stop (exit 0, promptly) that puts the run back in the queue.
  {
    ChildServer server(data.path());
    auto client = server.client();
    Json doc = getJson(*client, job);
    EXPECT_EQ(doc["runs"][0]["status"], "successful");
    EXPECT_EQ(doc["runs"][1]["status"], "successful");
    EXPECT_NE(doc["runs"][2]["status"], "failed");
    EXPECT_EQ(downloadFinishedRuns(*client, job, doc).at(1), before.at(1));
    ASSERT_TRUE(waitForDoc(*client, job, doc, [](const Json& d) {
      return d["runs"][2]["status"] == "successful" && d["runs"][3]["status"] == "running";
    }, 120)) << doc.dump(2);
    EXPECT_EQ(doc["runs"][2]["attempts"], 2);
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(server.stop(SIGTERM, 10), 0);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  }

  // 3. Restart again: the job finishes; results from before the kill are byte-identical and their
  //    files were never rewritten.
  {
    ChildServer server(data.path());
    auto client = server.client();
    Json doc = test::waitForJob(*client, id, {"successful", "failed", "dismissed"}, 120);
    ASSERT_EQ(doc["status"], "successful") << doc.dump(2);
    for (const auto& run : doc["runs"]) EXPECT_EQ(run["status"], "successful");
    EXPECT_FALSE(doc["runs"][0].contains("attempts"));  // ran once
    EXPECT_EQ(doc["runs"][3]["attempts"], 2);
    auto after = downloadFinishedRuns(*client, job, doc);
    ASSERT_EQ(after.size(), 4u);
    for (const auto& [k, bytes] : before) {
      EXPECT_EQ(after.at(k), bytes) << "run " << k << " changed after the crash";
      EXPECT_EQ(std::filesystem::last_write_time(runFile(k)), mtimes.at(k)) << "run " << k << " was rewritten";
    }
    EXPECT_EQ(getJson(*client, "/jobs")["numberMatched"], 1);
    EXPECT_EQ(server.stop(SIGTERM, 10), 0);
  }
}

}  // namespace
}  // namespace rupture::server
