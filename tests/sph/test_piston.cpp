// Pistons on the seed's 80 mm water column (2D slice, no gravity, c0 = 100 m/s to keep it short): the acoustic jump ρ0 c0 v (exactly, the Tait
// weak-shock value), its speed c0, its doubling at the rigid bottom; a free heavy piston's first
// peak ρ0 c0 V and the momentum it exchanges with the fluid.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "sph_test_support.hpp"

namespace rupture::testing {
namespace {

constexpr double kDiameter = 0.08, kHeight = 0.2, kSpacing = 0.002, kSoundSpeed = 100.0;

nlohmann::json columnSpec(const nlohmann::json& piston) {
  return {{"scenario", "piston-column"},
          {"dimension", 2},
          {"geometry", {{"diameter", kDiameter}, {"column_height", kHeight}}},
          {"resolution", {{"spacing", kSpacing}}},
          {"fluid", {{"sound_speed", kSoundSpeed}}},
          {"gravity", 0.0},
          {"piston", piston}};
}

/// Gauge pressures on the axis and the mean bottom pressure, sampled every step.
struct Record {
  std::vector<double> time, upper, middle, lower, bottom;
};

Record runColumn(sph::SphSystem& s, const ColumnLattice& g, double endTime,
                 const std::function<void()>& everyStep = [] {}) {
  Record r;
  const double H = g.H();
  while (s.time < endTime) {
    s.step(s.stableTimeStep(0.2));
    everyStep();
    r.time.push_back(s.time);
    r.upper.push_back(s.probePressure(0, 0.75 * H, 0));
    r.middle.push_back(s.probePressure(0, 0.5 * H, 0));
    r.lower.push_back(s.probePressure(0, 0.25 * H, 0));
    r.bottom.push_back(-s.bodies[kColumnBottom].force[1] / g.area);
  }
  return r;
}

double meanOver(const Record& r, const std::vector<double>& series, double t0, double t1) {
  double sum = 0;
  int count = 0;
  for (std::size_t k = 0; k < r.time.size(); ++k)
    if (r.time[k] >= t0 && r.time[k] <= t1) {
      sum += series[k];
      ++count;
    }
  return count ? sum / count : NAN;
}

/// First time the series reaches `level`, interpolated between samples.
double crossing(const Record& r, const std::vector<double>& series, double level) {
  for (std::size_t k = 1; k < series.size(); ++k)
    if (series[k] >= level && series[k - 1] < level)
      return r.time[k - 1] + (r.time[k] - r.time[k - 1]) * (level - series[k - 1]) / (series[k] - series[k - 1]);
  return NAN;
}

TEST(SphPiston, PrescribedPistonMakesTheAcousticJumpAtTheSoundSpeedDoubledAtTheBottom) {
  const double v = 2.0;
  const PistonColumnSpec spec = parsePistonColumnSpec(columnSpec({{"motion", "prescribed"}, {"speed", v}}));
  sph::SphSystem s;
  const ColumnLattice g = buildPistonColumn(s, spec);
  s.initialise();
  const double H = g.H(), h = s.model.h(), c0 = kSoundSpeed;
  const Record r = runColumn(s, g, 2.8 * H / c0);
  const sph::PistonShock shock = sph::pistonShock(s.model.eos, v);  // 1.02 ρ0 c0 v at v/c0 = 0.02

  // The plateau behind the front at mid-height, before the bottom's reflection comes back.
  const double jump = meanOver(r, r.middle, 0.5 * H / c0 + 8 * h / c0, 1.5 * H / c0 - 4 * h / c0);
  EXPECT_NEAR(jump / shock.pressure, 1.0, 0.05) << jump << " Pa against " << shock.pressure << " Pa";
  // The front's speed between the gauges at 3H/4 and H/4, from where each reaches half the jump.
  const double t1 = crossing(r, r.upper, 0.5 * shock.pressure), t2 = crossing(r, r.lower, 0.5 * shock.pressure);
  const double speed = 0.5 * H / (t2 - t1);
  EXPECT_NEAR(speed / c0, 1.0, 0.05) << speed << " m/s";
  // The rigid bottom reflects the wave: the fluid there stops and the pressure doubles.
  const double reflected = meanOver(r, r.bottom, H / c0 + 8 * h / c0, 2.6 * H / c0);
  EXPECT_NEAR(reflected / (2 * jump), 1.0, 0.10) << reflected << " Pa at the bottom, incident " << jump << " Pa";
}

TEST(SphPiston, FreeHeavyPistonExchangesMomentumWithTheFluidAndMakesTheAcousticPeak) {
  const double V = 2.0;
  // 100 times the column's mass per unit area (ρ0 H = 200 kg/m²), as the 3D mass on π D²/4.
  const double mass = 100.0 * 1000.0 * kHeight * 0.25 * std::numbers::pi * kDiameter * kDiameter;
  const PistonColumnSpec spec = parsePistonColumnSpec(columnSpec({{"motion", "free"}, {"mass", mass}, {"speed", V}}));
  sph::SphSystem s;
  const ColumnLattice g = buildPistonColumn(s, spec);
  s.initialise();
  const double H = g.H(), c0 = kSoundSpeed;
  const sph::RigidBody& piston = s.bodies[kColumnPiston];
  const std::array<double, 3> p0 = s.fluidMomentum();
  double worstMomentumError = 0, worstPistonError = 0;
  const Record r = runColumn(s, g, 1.4 * H / c0, [&] {
    // Newton's third law through the pair loop: what the fluid gained is what the bodies lost.
    const std::array<double, 3> p = s.fluidMomentum();
    double bodies = 0;
    for (const sph::RigidBody& b : s.bodies) bodies += b.impulse[1];
    const double scale = std::fabs(piston.impulse[1]) + 1e-30;
    worstMomentumError = std::max(worstMomentumError, std::fabs((p[1] - p0[1]) + bodies) / scale);
    // The piston's own momentum change is its force integral.
    worstPistonError = std::max(worstPistonError,
                                std::fabs(piston.mass * (piston.speed - V) -
                                          (piston.impulse[1] * piston.axis[1])) / scale);
  });
  EXPECT_LT(worstMomentumError, 1e-9);
  EXPECT_LT(worstPistonError, 1e-9);
  EXPECT_LT(piston.speed, V);  // the fluid decelerates it
  // The first peak at the gauge near the piston (3H/4): the bottom's reflection reaches it only
  // at 1.75 H/c0, after this run.
  double peak = 0;
  for (double p : r.upper) peak = std::max(peak, p);
  const double acoustic = 1000.0 * c0 * V;
  EXPECT_NEAR(peak / acoustic, 1.0, 0.10) << peak << " Pa against rho0 c0 V = " << acoustic << " Pa";
}

}  // namespace
}  // namespace rupture::testing
