// One cohesive beam against the closed-form clamped–clamped Euler–Bernoulli beam (André 2012):
// axial k = E S / L, end-displacement shear 12 E I δ / L³ with end moments 6 E I δ / L²,
// end rotation θ: near moment 4 E I θ / L, far moment 2 E I θ / L, shear 6 E I θ / L²,
// torsion G J ψ / L. Checked in 2D and 3D, and in a rotated frame.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "core/fast_math.hpp"
#include "core/bond_loop.hpp"
#include "dem/beam_forces.hpp"
#include "dem/beam_law.hpp"

using namespace rupture;

namespace {

constexpr double kRadius = 1e-3, kE = 70e9, kNu = 0.25, kRatio = 0.5;
constexpr double kL0 = 2 * kRadius;

struct Pair {
  ParticleStore p;
  BondStore bonds;
  BeamParameters beam{kE, kNu, kRatio, 0.0};
  explicit Pair(int dimension, Eigen::Vector3d axis = Eigen::Vector3d::UnitX()) {
    p.dimension = dimension;
    p.add(0, 0, 0, kRadius);
    const Eigen::Vector3d xj = kL0 * axis.normalized();
    p.add(xj.x(), xj.y(), xj.z(), kRadius);
    bonds.add(p, 0, 1);
    bonds.finalize(2);
  }
  void rotate(std::size_t k, const Eigen::Quaterniond& q) {
    const Eigen::Quaterniond now = q * Eigen::Quaterniond(p.qw[k], p.qx[k], p.qy[k], p.qz[k]);
    p.qw[k] = now.w(); p.qx[k] = now.x(); p.qy[k] = now.y(); p.qz[k] = now.z();
  }
  void move(std::size_t k, const Eigen::Vector3d& d) { p.x[k] += d.x(); p.y[k] += d.y(); p.z[k] += d.z(); }
  BeamResponse response() const { return beamResponseOf(beam, p, bonds, 0); }
};

Eigen::Vector3d forceJ(const BeamResponse& r) { return {r.fjx, r.fjy, r.fjz}; }
Eigen::Vector3d torqueI(const BeamResponse& r) { return {r.tix, r.tiy, r.tiz}; }
Eigen::Vector3d torqueJ(const BeamResponse& r) { return {r.tjx, r.tjy, r.tjz}; }

double relativeError(const Eigen::Vector3d& got, const Eigen::Vector3d& want) {
  return (got - want).norm() / want.norm();
}


const double kS = std::numbers::pi * std::pow(kRatio * kRadius, 2);
const double kI = std::numbers::pi * std::pow(kRatio * kRadius, 4) / 4;
const double kJ = 2 * kI;
const double kG = kE / (2 * (1 + kNu));

// A transverse end displacement δ also stretches the chord by δ²/2L and turns it by δ/L: the beam
// carries that (tiny) axial force along the current chord n and the shear across it. Compare each
// part with its closed form in that frame: F·n = −(E S/L0)(L − L0), F⊥ = shear·want⊥.
void expectShearInChordFrame(const Pair& b, const BeamResponse& r, const Eigen::Vector3d& transverse, double shear) {
  const Eigen::Vector3d d(b.p.x[1] - b.p.x[0], b.p.y[1] - b.p.y[0], b.p.z[1] - b.p.z[0]);
  const Eigen::Vector3d n = d.normalized();
  const Eigen::Vector3d f = forceJ(r);
  EXPECT_NEAR(f.dot(n), -kE * kS / kL0 * (d.norm() - kL0), 1e-9 * shear);
  const Eigen::Vector3d perpendicular = f - f.dot(n) * n;
  const Eigen::Vector3d want = transverse - transverse.dot(n) * n;
  EXPECT_LT(relativeError(perpendicular, -shear * want.normalized()), 1e-9);
}

class BeamBondInDimension : public ::testing::TestWithParam<int> {};

TEST_P(BeamBondInDimension, PureAxialStretchGivesESOverL) {
  Pair b(GetParam());
  const double delta = 1e-7;
  b.move(1, {delta, 0, 0});
  const BeamResponse r = b.response();
  EXPECT_LT(relativeError(forceJ(r), {-kE * kS / kL0 * delta, 0, 0}), 1e-9);
  EXPECT_LT(torqueI(r).norm(), 1e-9 * kE * kS / kL0 * delta * kL0);
  EXPECT_NEAR(r.axialForce, kE * kS / kL0 * delta, 1e-9 * kE * kS / kL0 * delta);
}

TEST_P(BeamBondInDimension, EndDisplacementShearMatchesClampedBeam) {
  Pair b(GetParam());
  const double delta = 1e-9;  // δ/L = 5e-7: geometric nonlinearity ~1e-13
  b.move(1, {0, delta, 0});
  const BeamResponse r = b.response();
  const double shear = 12 * kE * kI * delta / std::pow(kL0, 3);
  const double moment = 6 * kE * kI * delta / (kL0 * kL0);
  expectShearInChordFrame(b, r, {0, 1, 0}, shear);
  EXPECT_LT(relativeError(torqueI(r), {0, 0, moment}), 1e-9);
  EXPECT_LT(relativeError(torqueJ(r), {0, 0, moment}), 1e-9);
}

TEST_P(BeamBondInDimension, EndRotationBendingMatchesClampedBeam) {
  Pair b(GetParam());
  const double theta = 1e-4;
  b.rotate(1, Eigen::Quaterniond(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ())));
  const BeamResponse r = b.response();
  EXPECT_LT(relativeError(torqueJ(r), {0, 0, -4 * kE * kI * theta / kL0}), 1e-9);
  EXPECT_LT(relativeError(torqueI(r), {0, 0, -2 * kE * kI * theta / kL0}), 1e-9);
  EXPECT_LT(relativeError(forceJ(r), {0, 6 * kE * kI * theta / (kL0 * kL0), 0}), 1e-9);
}

// material.beam.bending_stress: the moment of eq. (1). An end rotation θ of j alone gives the end
// moments 2EIθ/L and 4EIθ/L: "end_moment" takes the larger, "relative_rotation" EIθ/L (σ = E r θ / L).
// A sideways end displacement turns the chord without turning the disks: "end_moment" sees the
// clamped moment 6EIδ/L², "relative_rotation" no bending at all (only the δ²/2L stretch).
TEST_P(BeamBondInDimension, BendingStressFollowsTheChosenMoment) {
  const double r = kRatio * kRadius;
  for (const bool relative : {false, true}) {
    SCOPED_TRACE(relative);
    Pair rotated(GetParam());
    rotated.beam.bendingFromRelativeRotation = relative;
    const double theta = 1e-4;
    rotated.rotate(1, Eigen::Quaterniond(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ())));
    const double moment = (relative ? 1.0 : 4.0) * kE * kI * theta / kL0;
    EXPECT_NEAR(rotated.response().equivalentStress, moment * r / kI, 1e-9 * moment * r / kI);

    Pair moved(GetParam());
    moved.beam.bendingFromRelativeRotation = relative;
    const double delta = 1e-9;
    moved.move(1, {0, delta, 0});
    const double clamped = 6 * kE * kI * delta / (kL0 * kL0) * r / kI;
    const double stretch = kE * (std::hypot(kL0, delta) - kL0) / kL0;
    EXPECT_NEAR(moved.response().equivalentStress, relative ? stretch : clamped + stretch, 1e-6 * clamped);
  }
}

INSTANTIATE_TEST_SUITE_P(TwoAndThreeD, BeamBondInDimension, ::testing::Values(2, 3));

TEST(BeamBond3D, TorsionGivesGJOverL) {
  Pair b(3);
  const double psi = 2e-4;
  b.rotate(1, Eigen::Quaterniond(Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitX())));
  const BeamResponse r = b.response();
  const double moment = kG * kJ * psi / kL0;
  EXPECT_LT(relativeError(torqueJ(r), {-moment, 0, 0}), 1e-9);
  EXPECT_LT(relativeError(torqueI(r), {moment, 0, 0}), 1e-9);
  EXPECT_LT(forceJ(r).norm(), 1e-9 * moment / kL0);
  EXPECT_NEAR(r.twist, psi, 1e-15);
}

TEST(BeamBond3D, OutOfPlaneBendingAndShearFollowTheSameLaw) {
  Pair b(3);
  const double delta = 1e-9;
  b.move(1, {0, 0, delta});
  const BeamResponse r = b.response();
  expectShearInChordFrame(b, r, {0, 0, 1}, 12 * kE * kI * delta / std::pow(kL0, 3));
  EXPECT_LT(relativeError(torqueI(r), {0, -6 * kE * kI * delta / (kL0 * kL0), 0}), 1e-9);
}

TEST(BeamBond3D, ResponseIsFrameInvariantAndBalanced) {
  // Same deformation in an arbitrarily rotated frame: loads rotate with it; forces and moments balance.
  const Eigen::Quaterniond frame(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  Pair a(3), b(3, frame * Eigen::Vector3d::UnitX());
  const Eigen::Vector3d d(3e-8, -2e-8, 5e-8);
  const Eigen::Quaterniond ri(Eigen::AngleAxisd(1e-4, Eigen::Vector3d(0.3, -1, 0.5).normalized()));
  const Eigen::Quaterniond rj(Eigen::AngleAxisd(2e-4, Eigen::Vector3d(-1, 0.2, 0.7).normalized()));
  a.move(1, d); a.rotate(0, ri); a.rotate(1, rj);
  b.move(1, frame * d); b.rotate(0, frame * ri * frame.conjugate()); b.rotate(1, frame * rj * frame.conjugate());
  const BeamResponse ra = a.response(), rb = b.response();
  EXPECT_LT(relativeError(forceJ(rb), frame * forceJ(ra)), 1e-9);
  EXPECT_LT(relativeError(torqueI(rb), frame * torqueI(ra)), 1e-9);
  EXPECT_LT(relativeError(torqueJ(rb), frame * torqueJ(ra)), 1e-9);
  EXPECT_NEAR(rb.equivalentStress, ra.equivalentStress, 1e-9 * ra.equivalentStress);
  // Moment balance about i: T_i + T_j + (x_j − x_i) × F_j = 0.
  const Eigen::Vector3d arm(a.p.x[1] - a.p.x[0], a.p.y[1] - a.p.y[0], a.p.z[1] - a.p.z[0]);
  const Eigen::Vector3d total = torqueI(ra) + torqueJ(ra) + arm.cross(forceJ(ra));
  EXPECT_LT(total.norm(), 1e-9 * torqueI(ra).norm());
}

TEST(BeamBond3D, ForceIsMinusEnergyGradient) {
  Pair b(3);
  b.move(1, {4e-8, 2e-8, -1e-8});
  b.rotate(0, Eigen::Quaterniond(Eigen::AngleAxisd(5e-5, Eigen::Vector3d(0, 0.6, 0.8))));
  const BeamResponse r = b.response();
  const double h = 1e-12;
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Vector3d step = Eigen::Vector3d::Zero();
    step[axis] = h;
    Pair plus = b, minus = b;
    plus.move(1, step);
    minus.move(1, -step);
    const double gradient = (plus.response().energy - minus.response().energy) / (2 * h);
    EXPECT_NEAR(-gradient, forceJ(r)[axis], 1e-5 * forceJ(r).norm()) << "axis " << axis;
  }
}

// A bond's stiffness factor f (disorder, inclusions) scales the law of E_μ after it is evaluated
// (dem/beam_law.hpp): it must be the beam of modulus f·E_μ to round-off, and f = 1 must leave every
// number of the unscaled law as it is, bit for bit.
TEST(BeamBond3D, StiffnessFactorIsTheBeamOfTheScaledModulus) {
  Pair b(3);
  b.move(1, {3e-6, -2e-6, 1.5e-6});
  b.rotate(0, Eigen::Quaterniond(Eigen::AngleAxisd(2e-3, Eigen::Vector3d(0.3, 1, -0.2).normalized())));
  b.rotate(1, Eigen::Quaterniond(Eigen::AngleAxisd(-1e-3, Eigen::Vector3d(1, 0.4, 0.7).normalized())));
  const BondGeometry g = bondGeometry<BeamLaw>(b.p, b.bonds, 0);
  ASSERT_EQ(g.stiffness, 1.0);
  const BeamLaw law{b.beam};
  const BondResponse unscaled = law.response(g);
  const BeamResponse direct = b.response();
  EXPECT_EQ(unscaled.fjx, direct.fjx);
  EXPECT_EQ(unscaled.tiy, direct.tiy);
  EXPECT_EQ(unscaled.equivalentStress, direct.equivalentStress);
  EXPECT_EQ(unscaled.energy, direct.energy);
  for (const double f : {0.37, 1.9}) {
    BondGeometry scaled = g;
    scaled.stiffness = f;
    BeamParameters stiffer = b.beam;
    stiffer.youngModulus *= f;
    const BondResponse got = BeamLaw{b.beam}.response(scaled);
    const BondResponse want = BeamLaw{stiffer}.response(g);
    const double loads[][2] = {{got.fjx, want.fjx}, {got.fjy, want.fjy}, {got.fjz, want.fjz},
                               {got.tix, want.tix}, {got.tiy, want.tiy}, {got.tiz, want.tiz},
                               {got.tjx, want.tjx}, {got.tjy, want.tjy}, {got.tjz, want.tjz},
                               {got.energy, want.energy}, {got.normalForce, want.normalForce},
                               {got.shearEnergy, want.shearEnergy}, {got.equivalentStress, want.equivalentStress}};
    for (const auto& [a, w] : loads) EXPECT_NEAR(a, w, 1e-13 * std::fabs(w)) << "f = " << f;
    EXPECT_EQ(got.stretch, want.stretch);
    const BondStiffness k = BeamLaw{b.beam}.stiffness(scaled), kWant = BeamLaw{stiffer}.stiffness(g);
    EXPECT_NEAR(k.translational, kWant.translational, 1e-13 * kWant.translational);
    EXPECT_NEAR(k.rotational, kWant.rotational, 1e-13 * kWant.rotational);
    b.bonds.stiffness[0] = f;  // the one-bond evaluation scales the same way
    EXPECT_EQ(b.response().fjx, got.fjx);
    b.bonds.stiffness[0] = 1.0;
  }
}

TEST(FastMath, Atan2MatchesTheLibraryEverywhere) {
  double worst = 0;
  for (int k = 0; k < 20000; ++k) {
    const double angle = -std::numbers::pi + 2 * std::numbers::pi * (k + 0.5) / 20000;
    for (double scale : {1e-8, 1.0, 3e5}) {
      const double y = scale * std::sin(angle), x = scale * std::cos(angle);
      worst = std::max(worst, std::abs(atan2Branchless(y, x) - std::atan2(y, x)));
    }
  }
  EXPECT_LT(worst, 1e-15);  // a few ulp of π
  EXPECT_EQ(atan2Branchless(0.0, 0.0), 0.0);
  EXPECT_NEAR(atan2Branchless(1e-300, 1.0), 1e-300, 1e-310);
}

}  // namespace
