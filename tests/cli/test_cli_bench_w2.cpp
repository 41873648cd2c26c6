// `rupture bench W2` through the real binary: the documented keys and the problem's size
// (bench/README.md: 100,000 sites, every pair within 3.015 dx bonded).
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace {

using rupture::testing::runCli;

TEST(CliBenchW2, PrintsOneJsonLineWithTheDocumentedKeys) {
  const auto r = runCli("bench W2 --steps 2 --threads 1");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  for (const char* key : {"workload", "particles", "bonds", "steps", "threads", "seconds", "particle_steps_per_s", "bond_steps_per_s"})
    EXPECT_TRUE(out.contains(key)) << key;
  EXPECT_EQ(out["workload"], "W2");
  EXPECT_EQ(out["particles"], 100000);
  EXPECT_EQ(out["steps"], 2);
  // Interior sites have 122 partners within 3.015 dx (61 bonds each); the surfaces have fewer.
  const double bondsPerSite = out["bonds"].get<double>() / out["particles"].get<double>();
  EXPECT_GT(bondsPerSite, 50.0);
  EXPECT_LT(bondsPerSite, 61.0);
  EXPECT_EQ(runCli("bench W2 --particles 10").exitCode, 2);  // W2 has a fixed size
  // W1's option on: a Weibull modulus in material.disorder's range, else exit 2 naming it.
  const auto off = runCli("bench W1 --stiffness-weibull 0.1 --steps 1");
  EXPECT_EQ(off.exitCode, 2);
  EXPECT_NE(off.err.find("--stiffness-weibull"), std::string::npos) << off.err;

  // The processor it ran on: /proc/cpuinfo's first "model name" and the L1 data cache the C
  // library reports (bench/README.md, "Output").
  ASSERT_TRUE(out.contains("host"));
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, modelName;
  while (std::getline(cpuinfo, line) && modelName.empty())
    if (line.rfind("model name", 0) == 0) modelName = line.substr(line.find(':') + 2);
  if (!modelName.empty()) {
    EXPECT_EQ(out["host"]["model_name"], modelName);
  }
  const long l1 = sysconf(_SC_LEVEL1_DCACHE_SIZE);
  if (l1 > 0) {
    EXPECT_EQ(out["host"]["l1d_bytes"], l1);
  } else {
    EXPECT_TRUE(out["host"]["l1d_bytes"].is_null());
  }
}

}  // namespace
