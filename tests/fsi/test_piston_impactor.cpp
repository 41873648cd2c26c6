// The impactor on the piston column (docs/sph.md, 3D, dx = 4 mm, rigid bottom, seed's 80 mm column
// of 203 mm): a 245 kg carriage strikes a 100 mm steel piston at 5 m/s (docs/tank-impact.md#impactor).
// The wave the piston's face launches carries ρ0 c0 times the face's speed (linear acoustics): a
// gauge at mid-height reads, over the plateau before the bottom's reflection comes back, ρ0 c0
// times the face's speed a wave transit earlier, within 5 %. The face of the elastic piston that
// the carriage only pushes (contact "compression_only") moves at nearly 2 V (the steel–water interface is nearly a free end for the steel's wave), so
// the incident pressure is nearly twice the rigid impactor's ρ0 c0 V.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "io/hdf5_file.hpp"
#include "rupture/run.hpp"
#include "rupture/spec_error.hpp"
#include "scenarios/piston_column/piston_column_spec.hpp"
#include "support/test_support.hpp"

namespace rupture {
namespace {

constexpr double kHeight = 0.203, kSoundSpeed = 1450.0, kGaugeHeight = 0.5 * kHeight;

nlohmann::json column(const nlohmann::json& impactor) {
  return {{"scenario", "piston-column"},
          {"dimension", 3},
          {"geometry", {{"diameter", 0.08}, {"column_height", kHeight}}},
          {"resolution", {{"spacing", 0.004}}},
          {"fluid", {{"sound_speed", kSoundSpeed}}},
          {"impactor", impactor},
          {"probes", {{0.0, 0.0, kGaugeHeight}}},
          {"run", {{"end_time", 2.0e-4}, {"output_interval", 2e-6}}}};
}

struct Series {
  std::vector<double> time, face, position, gauge;
  nlohmann::json summary;
};

Series run(const nlohmann::json& spec) {
  testing::ScratchDir dir;
  const std::string file = (dir.path() / "column.h5").string();
  RunControl control;
  const RunOutcome out = runSpec(spec, file, control, 1);
  EXPECT_TRUE(out.completed);
  const io::Hdf5File h5 = io::Hdf5File::openReadOnly(file);
  return {h5.readDatasetDouble("/series/time"), h5.readDatasetDouble("/series/piston_velocity"),
          h5.readDatasetDouble("/series/piston_position"), h5.readDatasetDouble("/series/probe_pressure_0"), out.summary};
}

double meanBetween(const Series& s, const std::vector<double>& v, double t0, double t1) {
  double sum = 0;
  int n = 0;
  for (std::size_t k = 0; k < s.time.size(); ++k)
    if (s.time[k] >= t0 && s.time[k] <= t1) sum += v[k], ++n;
  return sum / n;
}

/// Linear interpolation of a series at time t.
double valueAt(const Series& s, const std::vector<double>& v, double t) {
  for (std::size_t k = 1; k < s.time.size(); ++k)
    if (s.time[k] >= t) return v[k - 1] + (v[k] - v[k - 1]) * (t - s.time[k - 1]) / (s.time[k] - s.time[k - 1]);
  return v.back();
}

TEST(PistonImpactor, IncidentPressureIsRhoCTimesTheFaceSpeed) {
  for (const std::string model : {"elastic_piston", "two_body"}) {
    SCOPED_TRACE(model);
    const Series s = run(column({{"model", model}, {"contact", "compression_only"}, {"mass", 245.0}, {"speed", 5.0}}));
    // The face starts 19 µs after the strike (the steel's wave transit L/c), its wave reaches the
    // gauge (H − z)/c0 = 70 µs later with a front some 50 µs wide (the kernel and the artificial
    // viscosity spread it), and the bottom's reflection comes back at (H + z)/c0 = 210 µs: the
    // plateau from 120 to 190 µs, launched from 50 to 120 µs. The face's mean speed is its
    // displacement over that time (its own samples ring with the bar's modes).
    const double transit = (kHeight - kGaugeHeight) / kSoundSpeed, t0 = 1.2e-4, t1 = 1.9e-4;
    const double incident = meanBetween(s, s.gauge, t0, t1);
    const double face = (valueAt(s, s.position, t1 - transit) - valueAt(s, s.position, t0 - transit)) / (t1 - t0);
    const double rho0c0 = 1000.0 * kSoundSpeed;
    std::printf("%s: incident %.3g MPa, rho0 c0 face speed %.3g MPa (face %.3g m/s)\n", model.c_str(),
                incident / 1e6, rho0c0 * face / 1e6, face);
    EXPECT_NEAR(incident, rho0c0 * face, 0.05 * rho0c0 * face);
    // The face outruns the carriage: more than 1.5 V, at most 2 V.
    EXPECT_GT(face, 1.5 * 5.0);
    EXPECT_LT(face, 2.0 * 5.0);
    EXPECT_EQ(s.summary["impactor_model"], model);
  }
}

TEST(PistonImpactor, TiedCarriagePullsThePistonBackAfterItsFirstLeap) {
  // The carriage tied to the piston's top (contact "tied"): the face still leaps to nearly 2 V one
  // steel transit after the strike, but the carriage pulls the piston back when the bar's wave returns
  // to it as tension, so the face rings about the carriage's speed instead of flying off at nearly
  // 2 V, and the water's plateau is that of about V, not of the compression-only piston's 1.5-2 V.
  const Series s = run(column({{"model", "elastic_piston"}, {"contact", "tied"}, {"mass", 245.0}, {"speed", 5.0}}));
  const double transit = (kHeight - kGaugeHeight) / kSoundSpeed, t0 = 1.2e-4, t1 = 1.9e-4;
  const double incident = meanBetween(s, s.gauge, t0, t1);
  const double face = (valueAt(s, s.position, t1 - transit) - valueAt(s, s.position, t0 - transit)) / (t1 - t0);
  const double largest = *std::max_element(s.face.begin(), s.face.end()), rho0c0 = 1000.0 * kSoundSpeed;
  std::printf("tied: incident %.3g MPa, rho0 c0 face speed %.3g MPa (face %.3g m/s, largest %.3g m/s)\n",
              incident / 1e6, rho0c0 * face / 1e6, face, largest);
  EXPECT_GT(largest, 1.5 * 5.0);   // the first leap, as without the tie
  EXPECT_LT(face, 1.5 * 5.0);      // then pulled back: below the compression-only face's lower bound
  EXPECT_LT(incident, 1.5 * rho0c0 * 5.0);
  EXPECT_EQ(s.summary["impactor_model"], "elastic_piston");
}

TEST(PistonImpactor, RigidImpactorIsTheFreePiston) {
  const Series s = run(column({{"model", "rigid"}, {"mass", 245.0}, {"speed", 5.0}}));
  EXPECT_TRUE(s.summary["impactor_model"].is_null());
  EXPECT_DOUBLE_EQ(s.summary["piston_initial_speed"].get<double>(), 5.0);
  // The incident plateau: ρ0 c0 V within 5 % (docs/sph.md).
  const double incident = meanBetween(s, s.gauge, 1.2e-4, 1.9e-4);
  EXPECT_NEAR(incident, 1000.0 * kSoundSpeed * 5.0, 0.05 * 1000.0 * kSoundSpeed * 5.0);
}

// The impactor in the piston-column spec: 3D only, instead of `piston`, `rigid` is the free piston,
// and the resolved spec reads back to itself.
TEST(PistonImpactor, SpecTakesTheImpactorInsteadOfThePiston) {
  auto fieldOf = [](const nlohmann::json& spec) {
    try {
      parsePistonColumnSpec(spec);
    } catch (const SpecError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  nlohmann::json spec = column({{"model", "elastic_piston"}});
  const PistonColumnSpec parsed = parsePistonColumnSpec(spec);
  ASSERT_TRUE(parsed.impactor.has_value());
  EXPECT_DOUBLE_EQ(parsed.impactor->pistonDiameter, 0.08);  // the tube's bore
  const nlohmann::json resolved = toJson(parsed);
  EXPECT_EQ(toJson(parsePistonColumnSpec(resolved)), resolved);
  nlohmann::json flat = spec;
  flat["dimension"] = 2;
  flat["probes"] = {{0.0, 0.1}};
  EXPECT_EQ(fieldOf(flat), "impactor");
  nlohmann::json both = spec;
  both["piston"] = {{"motion", "free"}};
  EXPECT_EQ(fieldOf(both), "impactor");
  const PistonColumnSpec rigid = parsePistonColumnSpec(column({{"model", "rigid"}, {"mass", 100.0}, {"speed", 3.0}}));
  EXPECT_FALSE(rigid.impactor.has_value());
  EXPECT_EQ(rigid.piston.motion, sph::BodyMotion::Free);
  EXPECT_DOUBLE_EQ(rigid.piston.mass, 100.0);
  EXPECT_DOUBLE_EQ(rigid.piston.speed, 3.0);
  spec["impactor"]["piston"] = {{"elements", 0}};
  EXPECT_EQ(fieldOf(spec), "impactor.piston.elements");
}

}  // namespace
}  // namespace rupture
