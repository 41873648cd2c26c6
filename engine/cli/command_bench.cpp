#include <cstdlib>
#include <iostream>

#include "cli/cli.hpp"
#include "host_processor.hpp"
#include "bonded_bar_benchmark.hpp"
#include "pmb_impact_benchmark.hpp"
#include "tank_impact_benchmark.hpp"
#include "dam_break_benchmark.hpp"
#include "stream_benchmark.hpp"

namespace rupture::cli {

namespace {

/// Prints a benchmark's JSON line with the processor it ran on ("host").
void printReport(nlohmann::json report) {
  report["host"] = bench::hostProcessor();
  std::cout << report.dump() << std::endl;
}

/// Reads an integer option's value in [lo, hi] into `out` (an int or a size); false after printing
/// the usage error (exit code 2).
template <class T>
bool readInteger(const std::string& name, const std::string& value, long long lo, long long hi, T& out) {
  long long v = 0;
  if (!parseIntOption(name, value, lo, hi, v)) return false;
  out = static_cast<T>(v);
  return true;
}

/// Reads the "--threads N" and "--steps N" that follow the workload name (and "--spec FILE" where
/// `spec` is given: TANK); returns 0, or 2 after printing what is wrong.
int readThreadsAndSteps(const Args& args, const std::string& workload, int& threads, int& steps,
                        std::string* spec = nullptr) {
  for (std::size_t k = 1; k < args.size(); ++k) {
    if (k + 1 >= args.size()) return usageError("bench: option " + args[k] + " needs a value");
    if (args[k] == "--threads") {
      if (!readInteger("--threads", args[k + 1], 1, 1024, threads)) return 2;
    } else if (args[k] == "--steps") {
      if (!readInteger("--steps", args[k + 1], 1, 100000000, steps)) return 2;
    } else if (spec && args[k] == "--spec") {
      *spec = args[k + 1];
    } else {
      return usageError("bench " + workload + ": unknown option '" + args[k] + "'; allowed: --threads, --steps" +
                        (spec ? ", --spec" : ""));
    }
    ++k;
  }
  return 0;
}

/// rupture bench W2|W3|TANK [--threads N] [--steps N]: a workload that takes a thread count and a
/// step count (bench/README.md), run and reported.
template <class Options>
int benchThreadsAndSteps(const Args& args, nlohmann::json (*run)(const Options&)) {
  Options options;
  if (int code = readThreadsAndSteps(args, args[0], options.threads, options.steps)) return code;
  printReport(run(options));
  return 0;
}

/// rupture bench TANK-SEED [--threads N] [--end-time s] [--subcycling on|off]
/// [--step-estimate bound|spectral]: the seed's TF14A5
/// at the seed's inputs, run whole (bench/README.md).
int benchTankSeed(const Args& args) {
  bench::TankSeedOptions options;
  for (std::size_t k = 1; k < args.size(); ++k) {
    if (k + 1 >= args.size()) return usageError("bench: option " + args[k] + " needs a value");
    const std::string& value = args[k + 1];
    if (args[k] == "--threads") {
      if (!readInteger("--threads", value, 1, 1024, options.threads)) return 2;
    } else if (args[k] == "--end-time") {
      char* end = nullptr;
      const double t = std::strtod(value.c_str(), &end);
      if (end == value.c_str() || *end != '\0' || !(t > 0.0 && t <= 0.01))
        return usageError("bench TANK-SEED: --end-time = '" + value + "'; allowed: a time in (0, 0.01] s");
      options.endTime = t;
    } else if (args[k] == "--subcycling") {
      if (value != "on" && value != "off")
        return usageError("bench TANK-SEED: --subcycling = '" + value + "'; allowed: on, off");
      options.subcycling = value == "on" ? 1 : 0;
    } else if (args[k] == "--step-estimate") {
      if (value != "bound" && value != "spectral")
        return usageError("bench TANK-SEED: --step-estimate = '" + value + "'; allowed: bound, spectral");
      options.stepEstimate = value;
    } else {
      return usageError("bench TANK-SEED: unknown option '" + args[k] +
                        "'; allowed: --threads, --end-time, --subcycling, --step-estimate");
    }
    ++k;
  }
  printReport(bench::runTankSeedBenchmark(options));
  return 0;
}

/// rupture bench STREAM [--threads N] [--megabytes M]: the memory bandwidth the loops' roofline is
/// drawn against (bench/README.md, "Roofline"); M is the size of each of the three arrays in MiB.
int benchStream(const Args& args) {
  bench::StreamOptions options;
  for (std::size_t k = 1; k < args.size(); ++k) {
    if (k + 1 >= args.size()) return usageError("bench: option " + args[k] + " needs a value");
    if (args[k] == "--threads") {
      if (!readInteger("--threads", args[k + 1], 1, 1024, options.threads)) return 2;
    } else if (args[k] == "--megabytes") {
      // Three arrays of M MiB each: at most 3 × 4 GiB, what a machine of this kind can hold.
      if (!readInteger("--megabytes", args[k + 1], 1, 4096, options.megabytes)) return 2;
    } else {
      return usageError("bench STREAM: unknown option '" + args[k] + "'; allowed: --threads, --megabytes");
    }
    ++k;
  }
  printReport(bench::runStream(options));
  return 0;
}

}  // namespace

int benchCommand(const Args& args) {
  if (!args.empty() && args[0] == "W2") return benchThreadsAndSteps(args, bench::runW2);  // peridynamics
  if (!args.empty() && args[0] == "W3") return benchThreadsAndSteps(args, bench::runW3);  // SPH
  if (!args.empty() && args[0] == "TANK-SEED") return benchTankSeed(args);
  if (!args.empty() && args[0] == "STREAM") return benchStream(args);
  if (!args.empty() && args[0] == "TANK") {  // another tank-impact spec with --spec (the seed-resolution example)
    bench::TankImpactOptions options;
    if (int code = readThreadsAndSteps(args, args[0], options.threads, options.steps, &options.spec)) return code;
    printReport(bench::runTankImpactBenchmark(options));
    return 0;
  }
  if (args.empty() || args[0] != "W1")
    return usageError("bench: workload = '" + (args.empty() ? std::string() : args[0]) +
                      "'; allowed: W1, W2, W3, TANK, TANK-SEED, STREAM");
  bench::W1Options options;
  for (std::size_t k = 1; k < args.size(); ++k) {
    if (k + 1 >= args.size()) return usageError("bench: option " + args[k] + " needs a value");
    if (args[k] == "--threads") {
      if (!readInteger("--threads", args[k + 1], 1, 1024, options.threads)) return 2;
    } else if (args[k] == "--particles") {
      if (!readInteger("--particles", args[k + 1], 32, 100000000, options.particles)) return 2;
    } else if (args[k] == "--steps") {
      if (!readInteger("--steps", args[k + 1], 1, 100000000, options.steps)) return 2;
    } else if (args[k] == "--stiffness-weibull") {
      char* end = nullptr;
      const double m = std::strtod(args[k + 1].c_str(), &end);
      if (end == args[k + 1].c_str() || *end != '\0' || !(m >= 0.5 && m <= 1000))
        return usageError("bench: --stiffness-weibull = '" + args[k + 1] +
                          "'; allowed: a Weibull modulus from 0.5 to 1000 (material.disorder's range)");
      options.stiffnessWeibullModulus = m;
    } else {
      return usageError("bench: unknown option '" + args[k] + "'; allowed: --threads, --particles, --steps, "
                        "--stiffness-weibull");
    }
    ++k;
  }
  printReport(bench::runW1(options));
  return 0;
}

}  // namespace rupture::cli
