// The dam-break scenario through runSpec, as a user runs it: Martin & Moyce's column (a = 57 mm,
// H = 2a) in 2D until just before the surge reaches the far wall. The front must advance
// monotonically, no particle may leave the tank, the mass is exact, and the file keeps its contract.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "cli/cli_runner.hpp"
#include "io/hdf5_file.hpp"
#include "scenarios/dam_break/dam_break_lattice.hpp"
#include "scenarios/piston_column/piston_column_spec.hpp"
#include "support/test_support.hpp"

namespace rupture::testing {
namespace {

nlohmann::json damBreakSpec() {
  return {{"scenario", "dam-break"},
          {"dimension", 2},
          {"geometry", {{"column_width", 0.057}, {"column_height", 0.114}, {"tank_length", 0.4}, {"tank_height", 0.2}}},
          {"resolution", {{"spacing", 0.0025}}},
          {"probes", {{0.01, 0.005}, {0.2, 0.005}}},
          {"run", {{"end_time", 0.2}, {"snapshot_times", {0.0, 0.1}}}}};
}

TEST(DamBreak, FrontAdvancesMonotonicallyInsideTheTankWithExactMass) {
  ScratchDir dir;
  const std::string path = (dir / "dam.h5").string();
  RunControl control;
  const RunOutcome out = runSpec(damBreakSpec(), path, control, 1);
  ASSERT_TRUE(out.completed);
  EXPECT_EQ(out.summary["mass_error"].get<double>(), 0.0);
  EXPECT_EQ(out.summary["particles_outside_max"].get<std::int64_t>(), 0);

  const io::Hdf5File f = io::Hdf5File::openReadOnly(path);
  const std::vector<double> t = f.readDatasetDouble("/series/time");
  const std::vector<double> front = f.readDatasetDouble("/series/front_position");
  const std::vector<double> mass = f.readDatasetDouble("/series/fluid_mass");
  const std::vector<double> outside = f.readDatasetDouble("/series/particles_outside");
  ASSERT_GT(t.size(), 100u);
  EXPECT_NEAR(t.back(), 0.2, 1e-12);
  // The front starts at the (lattice-rounded) column width and only moves forward.
  EXPECT_DOUBLE_EQ(front.front(), f.readAttributeDouble("/geometry", "column_width"));
  for (std::size_t k = 1; k < front.size(); ++k) EXPECT_GE(front[k], front[k - 1]) << "row " << k << ", t " << t[k];
  EXPECT_GT(front.back(), 3.0 * front.front());  // it has surged (Z/a ≈ 4.5 at T = 3.7)
  for (std::size_t k = 0; k < t.size(); ++k) {
    EXPECT_EQ(mass[k], mass[0]);
    EXPECT_EQ(outside[k], 0.0) << "t " << t[k];
  }
  // The contract: units, probes, snapshots of every particle.
  EXPECT_EQ(f.readAttributeString("/summary", "front_position_final_unit"), "m");
  EXPECT_EQ(f.readAttributeString("/summary", "peak_pressure_unit"), "Pa");
  EXPECT_EQ(f.readAttributeString("/series/fluid_mass", "unit"), "kg/m");  // a 2D slice, per metre of depth
  for (const char* probe : {"/series/probe_pressure_0", "/series/probe_pressure_1"})
    EXPECT_EQ(f.datasetDims(probe), (std::vector<std::size_t>{t.size()}));
  EXPECT_EQ(f.readAttributeString("/series/probe_pressure_1", "position"), "[0.2,0.005]");
  const std::vector<std::string> snaps = f.listGroup("/snapshots");
  ASSERT_EQ(snaps.size(), 3u);  // 0, 0.1 and the final state
  const auto n = static_cast<std::size_t>(out.summary["particles"].get<std::int64_t>());
  for (const char* field : {"density", "pressure", "body"})
    EXPECT_EQ(f.datasetDims("/snapshots/000001/" + std::string(field)), (std::vector<std::size_t>{n}));
  EXPECT_EQ(f.datasetDims("/snapshots/000001/position"), (std::vector<std::size_t>{n, 3}));
}

/// The SpecError for a spec with `change` applied at JSON pointer `pointer`.
std::string rejected(nlohmann::json spec, const std::string& pointer, const nlohmann::json& value, std::string* message) {
  spec[nlohmann::json::json_pointer(pointer)] = value;
  try {
    validateSpec(spec);
  } catch (const SpecError& e) {
    *message = e.what();
    return e.field();
  }
  return "";
}

TEST(DamBreak, TrajectoriesAreBitwiseIdenticalOnOneAndTwoThreads) {
  // 1 mm spacing: about 9,000 particles, above the size at which the loops fork threads.
  nlohmann::json spec = damBreakSpec();
  spec["resolution"]["spacing"] = 0.001;
  const DamBreakSpec parsed = parseDamBreakSpec(spec);
  std::vector<double> x[2], rho[2];
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    sph::SphSystem s;
    buildDamBreak(s, parsed);
    ASSERT_GE(s.particles.size(), 8192u);
    s.skinFraction = 0.005;  // rebuild and re-sort within these few steps
    s.sortEvery = 1;
    s.initialise();
    for (int k = 0; k < 60; ++k) s.step(s.stableTimeStep(0.2));
    EXPECT_GE(s.listBuilds(), 3u);
    s.particles.inCreationOrder(s.particles.x, x[threads - 1]);
    s.particles.inCreationOrder(s.particles.rho, rho[threads - 1]);
  }
  omp_set_num_threads(1);
  EXPECT_TRUE(x[0] == x[1]);
  EXPECT_TRUE(rho[0] == rho[1]);
}

TEST(DamBreak, ResolvedSpecsParseBackToThemselves) {
  const nlohmann::json piston = {{"scenario", "piston-column"},
                                 {"dimension", 3},
                                 {"geometry", {{"diameter", 0.08}, {"column_height", 0.203}}},
                                 {"resolution", {{"spacing", 0.004}}},
                                 {"piston", {{"motion", "prescribed"}, {"speed_history", {{"time", {0.0, 1e-4}}, {"speed", {0.0, 3.0}}}}}},
                                 {"probes", {{0.0, 0.0, 0.1}}}};
  const nlohmann::json dam = toJson(parseDamBreakSpec(damBreakSpec()));
  EXPECT_EQ(toJson(parseDamBreakSpec(dam)), dam);
  EXPECT_EQ(dam["fluid"]["sound_speed"].get<double>(), 10.0 * std::sqrt(2.0 * 9.81 * 0.114));  // documented default
  EXPECT_EQ(dam["fluid"]["density_diffusion"]["model"], "fourtakas");
  const nlohmann::json column = toJson(parsePistonColumnSpec(piston));
  EXPECT_EQ(toJson(parsePistonColumnSpec(column)), column);
  EXPECT_EQ(column["fluid"]["sound_speed"].get<double>(), 1450.0);
  EXPECT_EQ(column["fluid"]["artificial_viscosity"]["alpha"].get<double>(), 0.3);
}

TEST(DamBreak, BadInputsAreRejectedNamingFieldValueAndRange) {
  const nlohmann::json dam = damBreakSpec();
  nlohmann::json piston = {{"scenario", "piston-column"},
                           {"geometry", {{"diameter", 0.08}, {"column_height", 0.203}}},
                           {"resolution", {{"spacing", 0.002}}}};
  EXPECT_EQ(rejectedField(dam), "");
  EXPECT_EQ(rejectedField(piston), "");
  struct Case {
    const nlohmann::json* spec;
    std::string pointer;
    nlohmann::json value;
    std::string field, valueText, allowed;
  };
  const Case cases[] = {
      {&dam, "/resolution/spacing", 0.0, "resolution.spacing", "0", "> 0"},
      {&dam, "/resolution/spacing", -0.001, "resolution.spacing", "-0.001", "> 0"},
      {&dam, "/resolution/spacing", 0.05, "resolution.spacing", "0.05", "<= 0.01425 m"},
      {&dam, "/fluid/sound_speed", -10.0, "fluid.sound_speed", "-10", "(0, 100000] (m/s)"},
      {&dam, "/probes/1", {0.5, 0.01}, "probes[1]", "[0.5,0.01]", "inside the tank"},
      {&dam, "/run/end_time", 0.0, "run.end_time", "0", "> 0"},
      {&dam, "/run/end_time", -1.0, "run.end_time", "-1", "> 0"},
      {&dam, "/geometry/column_width", 0.5, "geometry.tank_length", "0.4", ">= 0.5"},
      {&piston, "/resolution/spacing", 0.0, "resolution.spacing", "0", "> 0"},
      {&piston, "/resolution/spacing", 0.1, "resolution.spacing", "0.1", "<= 0.02 m"},
      {&piston, "/fluid/sound_speed", -1450.0, "fluid.sound_speed", "-1450", "(0, 100000] (m/s)"},
      {&piston, "/probes", {{0.05, 0.1}}, "probes[0]", "[0.05,0.1]", "inside the water column"},
      {&piston, "/run/end_time", 0.0, "run.end_time", "0", "> 0"},
      {&piston, "/piston/speed", -5.0, "piston.speed", "-5", "[0, 100000] (m/s)"},
  };
  for (const Case& c : cases) {
    std::string message;
    EXPECT_EQ(rejected(*c.spec, c.pointer, c.value, &message), c.field) << c.pointer;
    EXPECT_NE(message.find("= " + c.valueText), std::string::npos) << message;
    EXPECT_NE(message.find(c.allowed), std::string::npos) << message;
  }
}

TEST(DamBreak, CliExitsTwoOnBadInputAndRunsASmallPistonColumn) {
  ScratchDir dir;
  nlohmann::json bad = damBreakSpec();
  bad["resolution"]["spacing"] = -0.001;
  std::ofstream(dir / "bad.json") << bad.dump();
  const CliResult v = runCli("validate " + (dir / "bad.json").string());
  EXPECT_EQ(v.exitCode, 2);
  EXPECT_NE(v.err.find("resolution.spacing"), std::string::npos) << v.err;
  const CliResult r = runCli("run " + (dir / "bad.json").string() + " -o " + (dir / "bad.h5").string());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.h5"));

  const nlohmann::json piston = {{"scenario", "piston-column"},
                                 {"geometry", {{"diameter", 0.08}, {"column_height", 0.1}}},
                                 {"resolution", {{"spacing", 0.004}}},
                                 {"probes", {{0.0, 0.05}}},
                                 {"run", {{"end_time", 5e-5}}}};
  std::ofstream(dir / "piston.json") << piston.dump();
  const CliResult ok = runCli("run " + (dir / "piston.json").string() + " -o " + (dir / "piston.h5").string() + " --json");
  ASSERT_EQ(ok.exitCode, 0) << ok.err;
  const nlohmann::json summary = nlohmann::json::parse(ok.out);
  EXPECT_EQ(summary["completed"], 1);
  EXPECT_EQ(summary["acoustic_pressure"].get<double>(), 1000.0 * 1450.0 * 5.0);
  const std::string sidecar = readWhole(dir / "piston.xdmf2");
  EXPECT_NE(sidecar.find("Name=\"pressure\""), std::string::npos) << sidecar;
  EXPECT_NE(sidecar.find("Name=\"density\""), std::string::npos) << sidecar;
}

}  // namespace
}  // namespace rupture::testing
