// The server's log of a running run: a status line every --status-interval (the line `rupture run`
// prints off a terminal, io/status_line.hpp) and the timing breakdown when it ends.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <fstream>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "execution/scheduler.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {

/// Sends this process's stderr (where logLine writes) to a file while it lives, for the test to read.
class StderrToFile {
public:
  explicit StderrToFile(const std::filesystem::path& file) : m_file(file) {
    std::fflush(stderr);
    m_saved = ::dup(STDERR_FILENO);
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, STDERR_FILENO);
    ::close(fd);
  }
  ~StderrToFile() {
    std::fflush(stderr);
    ::dup2(m_saved, STDERR_FILENO);
    ::close(m_saved);
  }
  std::string text() const {
    std::fflush(stderr);
    std::ifstream in(m_file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

private:
  std::filesystem::path m_file;
  int m_saved = -1;
};

TEST(RunStatusLog, ARunningRunLogsItsStatusLineAndItsTimingAtTheEnd) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  std::atomic<bool> release{false};
  // A stand-in run: it says where it is, as a scenario's loop does, then waits to be released.
  auto executor = [&](const nlohmann::json&, const std::string& path, rupture::RunControl& control, int) {
    control.phases.enter("building the sample");
    control.phases.enter(rupture::kSteppingPhase);
    control.status.publish({.step = 4321, .time = 1.25e-9, .strain = 1.25e-3, .headlineName = "mean stress",
                            .headlineUnit = "Pa", .headline = 5.84e7, .brokenBonds = 17, .particles = 1000});
    control.progress = 0.4;
    while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    control.phases.enter("writing the result");
    std::ofstream(path) << "result";
    return rupture::RunOutcome{nlohmann::json::object(), true};
  };
  StderrToFile log(dir.path() / "server.log");
  Scheduler scheduler(store, dir.path(), 1, 1, executor);
  scheduler.setStatusInterval(1);
  scheduler.start();
  NewJob job;
  job.processId = "dynamic-tension";
  job.sweepMode = "grid";
  job.inputs = Json::object();
  job.sweep = Json::object();
  job.runs.emplace_back(Json::array(), Json::object());
  const auto id = store.createJob(job);
  scheduler.enqueue(id, 1);
  const std::string expected =
      "40 % | ETA unknown | step 4321 | time 1.25 ns | strain 0.00125 | mean stress 58.4 MPa | broken bonds 17";
  EXPECT_TRUE(test::waitFor([&] { return log.text().find(expected) != std::string::npos; }, 30)) << log.text();
  release = true;
  EXPECT_TRUE(test::waitFor([&] { return log.text().find("timing: total") != std::string::npos; }, 30)) << log.text();
  const std::string text = log.text();
  EXPECT_NE(text.find("job " + std::to_string(id)), std::string::npos) << text;
  EXPECT_NE(text.find(": timing: building the sample "), std::string::npos) << text;
  EXPECT_NE(text.find(": timing: time stepping "), std::string::npos) << text;
  EXPECT_NE(text.find(": timing: writing the result "), std::string::npos) << text;
  EXPECT_NE(text.find(": timing: total "), std::string::npos) << text;
  EXPECT_NE(text.find(" | 4321 steps | "), std::string::npos) << text;
  scheduler.shutdown();
}

}  // namespace
}  // namespace rupture::server
