// rupture-server configuration: flags, RUPTURE_* variables, precedence, errors, --help.
#include <map>

#include <gtest/gtest.h>

#include "common/config.hpp"

namespace rupture::server {
namespace {

EnvLookup envOf(std::map<std::string, std::string> vars) {
  return [vars](const std::string& name) -> std::optional<std::string> {
    auto it = vars.find(name);
    if (it == vars.end()) return std::nullopt;
    return it->second;
  };
}

TEST(ServerConfig, DefaultsMatchTheIssue) {
  ConfigResult r = parseConfig({}, envOf({}));
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.config.port, 8080);
  EXPECT_EQ(r.config.bind, "127.0.0.1");
  EXPECT_EQ(r.config.maxRuns, 1000);
  EXPECT_EQ(r.config.threadsPerRun, 1);
  EXPECT_TRUE(r.config.token.empty());
  EXPECT_GE(effectiveWorkers(r.config), 1);
}

TEST(ServerConfig, FlagsInBothSpellings) {
  ConfigResult r = parseConfig({"--port", "9000", "--bind=0.0.0.0", "--data-dir", "/tmp/x", "--workers=3",
                                "--threads-per-run", "2", "--max-runs", "50", "--max-request-bytes", "4096",
                                "--token", "s3cret", "--log-requests"},
                               envOf({}));
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.config.port, 9000);
  EXPECT_EQ(r.config.bind, "0.0.0.0");
  EXPECT_EQ(r.config.dataDir, "/tmp/x");
  EXPECT_EQ(r.config.workers, 3);
  EXPECT_EQ(r.config.threadsPerRun, 2);
  EXPECT_EQ(r.config.maxRuns, 50);
  EXPECT_EQ(r.config.maxRequestBytes, 4096u);
  EXPECT_EQ(r.config.token, "s3cret");
  EXPECT_TRUE(r.config.logRequests);
  EXPECT_EQ(effectiveWorkers(r.config), 3);
}

TEST(ServerConfig, EnvironmentVariablesAndFlagsWin) {
  auto env = envOf({{"RUPTURE_PORT", "7000"}, {"RUPTURE_TOKEN", "abc"}, {"RUPTURE_WORKERS", "5"},
                    {"RUPTURE_THREADS_PER_RUN", "4"}, {"RUPTURE_MAX_RUNS", "10"},
                    {"RUPTURE_MAX_REQUEST_BYTES", "2048"}, {"RUPTURE_DATA_DIR", "/srv/rupture"},
                    {"RUPTURE_BIND", "::1"}});
  ConfigResult r = parseConfig({"--port", "7001"}, env);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.config.port, 7001);
  EXPECT_EQ(r.config.token, "abc");
  EXPECT_EQ(r.config.workers, 5);
  EXPECT_EQ(r.config.threadsPerRun, 4);
  EXPECT_EQ(r.config.maxRuns, 10);
  EXPECT_EQ(r.config.maxRequestBytes, 2048u);
  EXPECT_EQ(r.config.dataDir, "/srv/rupture");
  EXPECT_EQ(r.config.bind, "::1");
}

TEST(ServerConfig, WorkersDefaultFromCoresAndThreadsPerRun) {
  ServerConfig c;
  c.workers = 0;
  c.threadsPerRun = 1;
  const int perCore = effectiveWorkers(c);
  c.threadsPerRun = 1000;
  EXPECT_EQ(effectiveWorkers(c), 1);
  EXPECT_GE(perCore, 1);
}

TEST(ServerConfig, BadValuesNameTheFlagOrVariable) {
  EXPECT_NE(parseConfig({"--port", "70000"}, envOf({})).error.find("--port"), std::string::npos);
  EXPECT_NE(parseConfig({"--workers", "two"}, envOf({})).error.find("not an integer"), std::string::npos);
  EXPECT_NE(parseConfig({"--threads-per-run", "0"}, envOf({})).error.find("out of range"), std::string::npos);
  EXPECT_NE(parseConfig({"--max-runs"}, envOf({})).error.find("needs a value"), std::string::npos);
  EXPECT_NE(parseConfig({"--frobnicate"}, envOf({})).error.find("unknown option"), std::string::npos);
  EXPECT_NE(parseConfig({"stray"}, envOf({})).error.find("unexpected argument"), std::string::npos);
  EXPECT_NE(parseConfig({}, envOf({{"RUPTURE_PORT", "x"}})).error.find("RUPTURE_PORT"), std::string::npos);
  EXPECT_NE(parseConfig({}, envOf({{"RUPTURE_LOG_REQUESTS", "maybe"}})).error.find("boolean"), std::string::npos);
}

TEST(ServerConfig, HelpListsEveryOptionWithItsVariable) {
  EXPECT_TRUE(parseConfig({"--help"}, envOf({})).showHelp);
  EXPECT_TRUE(parseConfig({"-h"}, envOf({})).showHelp);
  const std::string help = helpText();
  for (const char* s : {"--port", "RUPTURE_PORT", "--bind", "RUPTURE_BIND", "--data-dir", "RUPTURE_DATA_DIR",
                        "--workers", "RUPTURE_WORKERS", "--threads-per-run", "RUPTURE_THREADS_PER_RUN",
                        "--max-runs", "RUPTURE_MAX_RUNS", "--max-request-bytes", "RUPTURE_MAX_REQUEST_BYTES",
                        "--token", "RUPTURE_TOKEN", "8080", "127.0.0.1", "1000"}) {
    EXPECT_NE(help.find(s), std::string::npos) << s;
  }
}

}  // namespace
}  // namespace rupture::server
