// `rupture bench TANK-SEED` through the real binary: the documented keys, the seed's inputs, the
// shell's classes with subcycling on, and the options' errors (exit 2 naming the option).
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace {

using rupture::testing::runCli;

TEST(CliBenchTankSeed, PrintsOneJsonLineWithTheDocumentedKeys) {
  const auto r = runCli("bench TANK-SEED --end-time 1e-6 --subcycling on --step-estimate bound --threads 1");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  for (const char* key : {"workload", "threads", "subcycling", "end_time_s", "sph_particles", "plate_nodes", "fluid_steps",
                          "shell_fine_steps", "shell_fine_steps_per_fluid_step", "shell_coarsest_class",
                          "shell_points_per_class", "shell_point_evaluations", "wall_seconds", "fluid_seconds",
                          "shell_seconds", "contact_seconds", "shell_profile_s", "fluid_particle_steps_per_s",
                          "shell_node_updates_per_s", "shell_point_evaluations_per_s", "time_to_fracture_s",
                          "first_pressure_peak_pa", "step_estimate", "shell_spectrum_measurements",
                          "shell_max_frequency_rad_s", "host"})
    EXPECT_TRUE(out.contains(key)) << key;
  // The seed's plate: 0.5 mm rings at the step, 2 mm elsewhere (docs/tank-impact.md: 13,034 nodes).
  EXPECT_EQ(out["plate_nodes"], 13034);
  EXPECT_EQ(out["subcycling"], true);
  EXPECT_GE(out["shell_coarsest_class"].get<int>(), 2);
  // Fewer stress-point evaluations than nodes × shell steps: what the classes save.
  EXPECT_LT(out["shell_point_evaluations"].get<double>(),
            0.5 * out["plate_nodes"].get<double>() * out["shell_fine_steps"].get<double>());
  for (const char* part : {"gradients", "layers", "forces", "integration", "fracture"})
    EXPECT_GE(out["shell_profile_s"][part].get<double>(), 0.0) << part;

  // Off: the single rate, every point at every step, and said so.
  const auto single = runCli("bench TANK-SEED --end-time 1e-6 --subcycling off --step-estimate bound --threads 1");
  ASSERT_EQ(single.exitCode, 0) << single.err;
  const auto offOut = nlohmann::json::parse(single.out);
  EXPECT_EQ(offOut["subcycling"], false);
  EXPECT_EQ(offOut["shell_coarsest_class"], 0);
  EXPECT_EQ(offOut["shell_point_evaluations"].get<double>(),
            offOut["plate_nodes"].get<double>() * offOut["shell_fine_steps"].get<double>());
  EXPECT_EQ(offOut["step_estimate"], "bound");
  EXPECT_EQ(offOut["shell_spectrum_measurements"], 0);
  EXPECT_TRUE(offOut["shell_max_frequency_rad_s"].is_null());

  // The defaults: the measured spectrum at the single rate, fewer and longer steps (5.8 times the
  // bound's frequency on this plate).
  const auto measured = runCli("bench TANK-SEED --end-time 1e-6 --threads 1");
  ASSERT_EQ(measured.exitCode, 0) << measured.err;
  const auto spectral = nlohmann::json::parse(measured.out);
  EXPECT_EQ(spectral["step_estimate"], "spectral");
  EXPECT_EQ(spectral["subcycling"], false);
  EXPECT_GE(spectral["shell_spectrum_measurements"].get<int>(), 1);
  EXPECT_GT(spectral["shell_max_frequency_rad_s"].get<double>(), 0.0);
  EXPECT_GE(spectral["shell_profile_s"]["spectrum"].get<double>(), 0.0);
  EXPECT_LT(3.0 * spectral["shell_fine_steps"].get<double>(), offOut["shell_fine_steps"].get<double>());
}

TEST(CliBenchTankSeed, BadOptionsExitTwoNamingThem) {
  for (const auto& [args, name] : {std::pair{"--end-time 0", "--end-time"}, std::pair{"--end-time 1", "--end-time"},
                                   std::pair{"--subcycling maybe", "--subcycling"}, std::pair{"--threads 0", "--threads"},
                                   std::pair{"--step-estimate exact", "--step-estimate"},
                                   std::pair{"--steps 3", "--steps"}}) {
    const auto r = runCli(std::string("bench TANK-SEED ") + args);
    EXPECT_EQ(r.exitCode, 2) << args;
    EXPECT_NE(r.err.find(name), std::string::npos) << args << ": " << r.err;
  }
}

}  // namespace
