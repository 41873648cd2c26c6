// `rupture bench STREAM` through the real binary: the documented keys, bandwidths that a memory
// system can give, and options outside their ranges refused (bench/README.md, "Roofline").
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace {

using rupture::testing::runCli;

TEST(CliBenchStream, PrintsOneJsonLineWithPositiveBandwidths) {
  // 16 MiB arrays: small enough for a test, large enough to time (the default is 128 MiB).
  const auto r = runCli("bench STREAM --threads 1 --megabytes 16");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  EXPECT_EQ(out["workload"], "STREAM");
  EXPECT_EQ(out["threads"], 1);
  EXPECT_EQ(out["megabytes"], 16);
  EXPECT_EQ(out["elements"], 16 * 1024 * 1024 / 8);
  EXPECT_TRUE(out["valid"].get<bool>());  // every element holds what the kernels imply
  for (const char* kernel : {"copy", "scale", "add", "triad"}) {
    const std::string key = std::string(kernel) + "_gb_per_s";
    ASSERT_TRUE(out.contains(key)) << key;
    // Positive, and below what any memory system of this decade gives one thread (1 TB/s): a
    // zero or an absurd figure means a timer or byte count is wrong.
    EXPECT_GT(out[key].get<double>(), 0.0) << key;
    EXPECT_LT(out[key].get<double>(), 1000.0) << key;
    EXPECT_GT(out[std::string(kernel) + "_best_seconds"].get<double>(), 0.0) << kernel;
  }
  ASSERT_TRUE(out.contains("host"));
  EXPECT_TRUE(out["host"].contains("model_name"));
  EXPECT_TRUE(out.contains("l3_bytes"));
}

TEST(CliBenchStream, RefusesBadOptionsNamingThem) {
  for (const char* bad : {"bench STREAM --megabytes 0", "bench STREAM --megabytes 100000",
                          "bench STREAM --megabytes x", "bench STREAM --threads 0"}) {
    const auto r = runCli(bad);
    EXPECT_EQ(r.exitCode, 2) << bad;
    const std::string option = std::string(bad).find("--megabytes") != std::string::npos ? "--megabytes" : "--threads";
    EXPECT_NE(r.err.find(option), std::string::npos) << bad << ": " << r.err;
  }
  const auto unknown = runCli("bench STREAM --steps 3");
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_NE(unknown.err.find("--steps"), std::string::npos) << unknown.err;
  EXPECT_NE(unknown.err.find("--megabytes"), std::string::npos) << unknown.err;  // what is allowed
  const auto missing = runCli("bench STREAM --megabytes");
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find("--megabytes"), std::string::npos) << missing.err;
}

}  // namespace
