// The drop-tower impactor without water (fsi/impactor_column.hpp): a carriage striking a free piston.
// Against the one-dimensional solutions of docs/tank-impact.md#impactor:
// - elastic piston (Saint-Venant's rigid mass on a free bar): while they touch, the carriage
//   obeys M dv/dt = −Z A v (Z = ρ c, c = √(E/ρ)); the wave reflected at the free end reaches the
//   struck face at T = 2L/c as tension and the two part there. So the carriage leaves at
//   V e^(−T/τ), τ = M/(Z A), and the piston's mean speed is M V (1 − e^(−T/τ)) / m;
// - rigid piston (`two_body`): an elastic collision, piston 2M V/(M + m), carriage (M − m) V/(M + m).
// - tied contact (`contact: tied`), rigid piston: the carriage and the piston a two-mass oscillator,
//   closure (u_carriage − u_piston) = (V/ω) sin ω t with ω² = k_c (M + m)/(M m), the centre of mass
//   moving on at M V/(M + m); they never part.
// Momentum is conserved to round-off and energy (kinetic + elastic) to the integrator's error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fsi/impactor_column.hpp"
#include "scenarios/fluid/impactor_spec.hpp"
#include "rupture/spec_error.hpp"

namespace rupture::fsi {
namespace {

struct BarCase {
  double carriageMass, length;
  int elements;
};

/// The drop tower as built: the carriage pushes the piston and may part from it.
ImpactorSpec elasticPiston(const BarCase& c) {
  ImpactorSpec s;
  s.model = ImpactorModel::ElasticPiston;
  s.contact = CarriageContact::CompressionOnly;
  s.mass = c.carriageMass;
  s.speed = 5.0;
  s.pistonLength = c.length;
  s.pistonElements = c.elements;
  return s;
}

/// Runs the column with no face force for `duration` in steps of dt; returns the largest relative
/// energy drift seen.
double runFree(ImpactorColumn& column, double duration, double dt, double energy0) {
  double drift = 0.0;
  for (double t = 0; t < duration; t += dt) {
    column.advance(dt, 0.0);
    drift = std::max(drift, std::fabs(column.kineticEnergy() + column.elasticEnergy() - energy0) / energy0);
  }
  return drift;
}

TEST(ImpactorColumn, ElasticPistonLeavesAtTheBarImpactSpeed) {
  for (const BarCase& c : {BarCase{245.0, 0.1, 20}, BarCase{20.0, 0.1, 20}, BarCase{245.0, 0.3, 60}, BarCase{5.0, 0.2, 40}}) {
    const ImpactorSpec s = elasticPiston(c);
    ImpactorColumn column(s, 0.0);
    const double m = s.pistonMass(), c0 = std::sqrt(s.pistonYoungModulus / s.pistonDensity);
    const double T = 2.0 * c.length / c0, tau = c.carriageMass / (s.pistonDensity * c0 * s.pistonArea());
    const double p0 = column.momentum(), e0 = column.kineticEnergy();
    // Past the separation at T, with time for the carriage to fall behind.
    const double drift = runFree(column, 2.0 * T, 1e-7, e0);
    const double carriage = s.speed * std::exp(-T / tau);
    const double piston = c.carriageMass * s.speed * (1.0 - std::exp(-T / tau)) / m;
    SCOPED_TRACE("M = " + std::to_string(c.carriageMass) + " kg, L = " + std::to_string(c.length) + " m");
    std::printf("M %g kg, L %g m: piston %.4f m/s (solution %.4f), carriage %.4f m/s (%.4f), energy drift %.1e\n",
                c.carriageMass, c.length, column.pistonSpeed(), piston, column.carriageSpeed(), carriage, drift);
    EXPECT_EQ(column.contactForce(), 0.0);  // parted
    EXPECT_NEAR(column.pistonSpeed(), piston, 0.05 * piston);
    EXPECT_NEAR(column.carriageSpeed(), carriage, 0.05 * (s.speed - carriage) + 1e-3 * s.speed);
    EXPECT_NEAR(column.momentum(), p0, 1e-12 * std::fabs(p0));
    EXPECT_LT(drift, 2e-3);
    // The wave has reached the wetted face and moved it (the next test times its arrival).
    EXPECT_GT(column.faceDisplacement(), 0.0);
  }
}

TEST(ImpactorColumn, FaceStartsMovingOneWaveTransitAfterTheStrike) {
  const ImpactorSpec s = elasticPiston({245.0, 0.2, 80});
  ImpactorColumn column(s, 0.0);
  const double c0 = std::sqrt(s.pistonYoungModulus / s.pistonDensity), transit = s.pistonLength / c0;
  double firstMove = -1;
  for (double t = 0; t < 2 * transit; t += 1e-8) {
    column.advance(1e-8, 0.0);
    if (firstMove < 0 && column.faceSpeed() > 0.05 * s.speed) firstMove = t;
  }
  EXPECT_NEAR(firstMove, transit, 0.1 * transit);
  // A free face doubles the incident particle speed: 2 V while the pulse is reflected.
  EXPECT_NEAR(column.faceSpeed(), 2 * s.speed * std::exp(-transit / (s.mass / (s.pistonDensity * c0 * s.pistonArea()))),
              0.1 * s.speed);
}

TEST(ImpactorColumn, RigidPistonCollidesElastically) {
  for (double M : {245.0, 10.0, 2.0}) {
    ImpactorSpec s;
    s.model = ImpactorModel::TwoBody;
    s.contact = CarriageContact::CompressionOnly;
    s.mass = M;
    s.speed = 2.0;
    ImpactorColumn column(s, 0.0);
    const double m = s.pistonMass(), p0 = column.momentum(), e0 = column.kineticEnergy();
    const double contactTime = std::numbers::pi * std::sqrt(M * m / (M + m) / s.resolvedContactStiffness());
    const double drift = runFree(column, 3.0 * contactTime, contactTime / 200, e0);
    SCOPED_TRACE("M = " + std::to_string(M) + " kg");
    EXPECT_EQ(column.contactForce(), 0.0);
    EXPECT_NEAR(column.pistonSpeed(), 2 * M * s.speed / (M + m), 5e-3 * s.speed);
    EXPECT_NEAR(column.carriageSpeed(), (M - m) * s.speed / (M + m), 5e-3 * s.speed);
    EXPECT_NEAR(column.momentum(), p0, 1e-12 * p0);
    EXPECT_LT(drift, 2e-3);
  }
}

TEST(ImpactorColumn, TiedCarriageAndPistonOscillateTogether) {
  for (double M : {245.0, 10.0}) {
    ImpactorSpec s;
    s.model = ImpactorModel::TwoBody;
    s.contact = CarriageContact::Tied;
    s.mass = M;
    ImpactorColumn column(s, 0.0);
    const double m = s.pistonMass(), k = s.resolvedContactStiffness();
    const double omega = std::sqrt(k * (M + m) / (M * m)), period = 2 * std::numbers::pi / omega;
    const double p0 = column.momentum(), e0 = column.kineticEnergy(), dt = period / 400;
    double drift = 0.0, largestTension = 0.0, largestError = 0.0;
    for (int step = 1; step <= 1000; ++step) {  // 2.5 periods: the pull of the first rebound included
      column.advance(dt, 0.0);
      const double closure = column.carriageDisplacement() - column.faceDisplacement();
      largestError = std::max(largestError, std::fabs(closure - s.speed / omega * std::sin(omega * step * dt)));
      largestTension = std::max(largestTension, -column.contactForce());
      drift = std::max(drift, std::fabs(column.kineticEnergy() + column.elasticEnergy() - e0) / e0);
    }
    SCOPED_TRACE("M = " + std::to_string(M) + " kg");
    EXPECT_LT(largestError, 1e-3 * s.speed / omega);
    EXPECT_NEAR(largestTension, k * s.speed / omega, 1e-3 * k * s.speed / omega);  // the spring pulls as it pushes
    EXPECT_NEAR(column.momentum(), p0, 1e-12 * p0);
    EXPECT_LT(drift, 2e-3);
  }
}

TEST(ImpactorColumn, FaceForceWorkAndGravity) {
  // A constant resisting face force: momentum changes by F t, and the face force's work balances
  // the energy (kinetic + elastic) to the integrator's error.
  ImpactorSpec s = elasticPiston({245.0, 0.1, 20});
  ImpactorColumn column(s, 0.0);
  const double F = -2e4, p0 = column.momentum(), e0 = column.kineticEnergy();
  const double dt = 1e-6;
  for (int k = 0; k < 500; ++k) column.advance(dt, F);
  EXPECT_NEAR(column.momentum(), p0 + F * 500 * dt, 1e-9 * p0);
  EXPECT_NEAR(column.kineticEnergy() + column.elasticEnergy(), e0 + column.faceWork(), 2e-3 * e0);
  // Gravity alone, nothing struck: every point falls together.
  s.speed = 0.0;
  ImpactorColumn falling(s, 9.81);
  for (int k = 0; k < 100; ++k) falling.advance(1e-5, 0.0);
  EXPECT_NEAR(falling.carriageSpeed(), 9.81e-3, 1e-9);
  EXPECT_NEAR(falling.pistonSpeed(), 9.81e-3, 1e-9);
}

TEST(ImpactorSpec, DefaultsAndErrorsNameTheField) {
  auto parse = [](const nlohmann::json& j) { return rupture::parseImpactor(io::SpecReader(j, "impactor"), 0.08, 3e-3); };
  const ImpactorSpec d = parse(nlohmann::json::object());
  EXPECT_EQ(d.model, ImpactorModel::ElasticPiston);
  EXPECT_DOUBLE_EQ(d.mass, 245.0);
  EXPECT_DOUBLE_EQ(d.pistonDiameter, 0.08);
  EXPECT_DOUBLE_EQ(d.pistonYoungModulus, 211e9);  // seed Table 2, APX steel
  EXPECT_DOUBLE_EQ(d.pistonDensity, 7700.0);
  EXPECT_NEAR(d.resolvedContactStiffness(), 211e9 * d.pistonArea() / 0.005, 1.0);
  EXPECT_EQ(d.contact, CarriageContact::Tied);
  EXPECT_EQ(parse({{"contact", "compression_only"}}).contact, CarriageContact::CompressionOnly);
  // The resolved spec reads back to itself.
  const nlohmann::json resolved = rupture::toJson(d);
  EXPECT_EQ(rupture::toJson(parse(resolved)), resolved);
  // A piston mass sets the density.
  const ImpactorSpec heavy = parse({{"piston", {{"mass", 10.0}}}});
  EXPECT_NEAR(heavy.pistonMass(), 10.0, 1e-12);
  auto fieldOf = [&](const nlohmann::json& j) {
    try {
      parse(j);
    } catch (const SpecError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(fieldOf({{"model", "spring"}}), "impactor.model");
  EXPECT_EQ(fieldOf({{"model", "rigid"}, {"piston", {{"length", 0.1}}}}), "impactor.piston");
  EXPECT_EQ(fieldOf({{"model", "two_body"}, {"piston", {{"elements", 4}}}}), "impactor.piston.elements");
  EXPECT_EQ(fieldOf({{"piston", {{"mass", 4.0}, {"density", 7000.0}}}}), "impactor.piston.mass");
  EXPECT_EQ(fieldOf({{"piston", {{"length", -0.1}}}}), "impactor.piston.length");
  EXPECT_EQ(fieldOf({{"piston", {{"elements", 0}}}}), "impactor.piston.elements");
  EXPECT_EQ(fieldOf({{"piston", {{"stiffness", 1.0}}}}), "impactor.piston.stiffness");
  EXPECT_EQ(fieldOf({{"mass", 0.0}}), "impactor.mass");
  EXPECT_EQ(fieldOf({{"contact", "glued"}}), "impactor.contact");
  EXPECT_EQ(fieldOf({{"model", "rigid"}, {"contact", "tied"}}), "impactor.contact");
  // A contact so stiff that the column would never finish.
  EXPECT_EQ(fieldOf({{"contact_stiffness", 1e16}, {"piston", {{"elements", 1000}}}}), "impactor.contact_stiffness");
}

}  // namespace
}  // namespace rupture::fsi
