// The generic suite every registered bond law passes (core/bond_law.hpp): forces and torques are
// −dE/dx and −dE/dθ (central finite differences), the pair balances forces and moments, the result
// does not depend on a rigid rotation of the whole configuration nor on the order of the particles,
// and the spec rejects bad parameters naming the field. The suite runs every registered material
// style (bonded/materials/registry.cpp) on its own example block: a new style is tested by being
// registered.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <string>

#include "bonded/bonded_system.hpp"
#include "bonded/materials/registry.hpp"
#include "bonded/bonded_spec.hpp"
#include "support/test_support.hpp"

namespace rupture {
namespace {

constexpr double kL0 = 1e-3;  // m
constexpr double kRadius = 0.5 * kL0;

struct LawCase {
  std::string name;
  std::function<void(BondedSystem&)> install;  // sets the model and the per-bond constants
  bool rotational = false;                     // the law produces torques (checked against dE/dθ)
};

/// A style's example material on a two-site piece of its example lattice of spacing L0: the spec
/// parsed as a run would parse it, the bond set up by the style.
LawCase styleCase(const MaterialStyle& style) {
  const MaterialExample example = style.example();
  const nlohmann::json spec = {{"dimension", 3},
                               {"sample", {{"lattice", example.lattice}, {"size", {8 * kL0, 8 * kL0, 8 * kL0}}, {"spacing", kL0}}},
                               {"material", example.material}};
  const io::SpecReader root(spec, "");
  const SampleSpec sample = io::parseSample(root);
  const MaterialSpec material = io::parseMaterial(root);
  const MaterialStyle* chosen = &style;
  return {std::string(style.name()),
          [sample, material, chosen](BondedSystem& s) { chosen->assign(s, sample, material); },
          std::visit([](const auto& m) { return std::decay_t<decltype(m)>::Law::kRotational; },
                     [&] { BondedSystem probe; chosen->assign(probe, sample, material); return probe.model; }())};
}

std::vector<LawCase> everyStyle() {
  std::vector<LawCase> cases;
  for (const MaterialStyle* style : materialStyles()) cases.push_back(styleCase(*style));
  return cases;
}

/// Two bonded spheres, the bond created at rest along `axis`, then the configuration set by the test.
struct Pair {
  BondedSystem s;
  Pair(const LawCase& law, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    s.particles.dimension = 3;
    s.particles.add(a.x(), a.y(), a.z(), kRadius);
    s.particles.add(b.x(), b.y(), b.z(), kRadius);
    s.particles.setMassFromDensity(2500, 0);
    s.bonds.add(s.particles, 0, 1);
    law.install(s);
    s.initialize();
  }
  void place(int k, const Eigen::Vector3d& x, const Eigen::Quaterniond& q) {
    ParticleStore& p = s.particles;
    p.x[k] = x.x(); p.y[k] = x.y(); p.z[k] = x.z();
    p.qw[k] = q.w(); p.qx[k] = q.x(); p.qy[k] = q.y(); p.qz[k] = q.z();
  }
  Eigen::Vector3d x(int k) const { return {s.particles.x[k], s.particles.y[k], s.particles.z[k]}; }
  Eigen::Quaterniond q(int k) const { return {s.particles.qw[k], s.particles.qx[k], s.particles.qy[k], s.particles.qz[k]}; }
  double energy() { return s.bondEnergy(); }
  Eigen::Vector3d force(int k) {
    s.initialize();
    return {s.particles.fx[k], s.particles.fy[k], s.particles.fz[k]};
  }
  Eigen::Vector3d torque(int k) {
    s.initialize();
    return {s.particles.tx[k], s.particles.ty[k], s.particles.tz[k]};
  }
};

/// A loaded configuration: stretched, sheared and with both ends rotated (all about 1e-3).
void deform(Pair& pair) {
  const Eigen::Vector3d xj = pair.x(1) + kL0 * Eigen::Vector3d(1.2e-3, -0.8e-3, 0.6e-3);
  pair.place(1, xj, Eigen::Quaterniond(Eigen::AngleAxisd(1.5e-3, Eigen::Vector3d(0.3, -0.5, 0.8).normalized())));
  pair.place(0, pair.x(0), Eigen::Quaterniond(Eigen::AngleAxisd(-0.9e-3, Eigen::Vector3d(-0.7, 0.2, 0.4).normalized())));
}

class BondLawSuite : public ::testing::TestWithParam<LawCase> {};

TEST_P(BondLawSuite, ForcesAndTorquesAreMinusTheEnergyGradient) {
  Pair pair(GetParam(), {0, 0, 0}, {kL0, 0, 0});
  deform(pair);
  const double h = 1e-7 * kL0, angle = 1e-7;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3d f = pair.force(k), t = pair.torque(k);
    const Eigen::Vector3d x0 = pair.x(k);
    const Eigen::Quaterniond q0 = pair.q(k);
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(a);
      pair.place(k, x0 + h * e, q0);
      const double up = pair.energy();
      pair.place(k, x0 - h * e, q0);
      const double down = pair.energy();
      pair.place(k, x0, q0);
      // Corotational beams and Born springs are exact to first order in the end rotations (1e-3).
      EXPECT_NEAR(f[a], -(up - down) / (2 * h), 5e-3 * f.norm() + 1e-12) << GetParam().name << " force " << k << a;
      if (!GetParam().rotational) continue;
      pair.place(k, x0, Eigen::Quaterniond(Eigen::AngleAxisd(angle, e)) * q0);
      const double turnUp = pair.energy();
      pair.place(k, x0, Eigen::Quaterniond(Eigen::AngleAxisd(-angle, e)) * q0);
      const double turnDown = pair.energy();
      pair.place(k, x0, q0);
      EXPECT_NEAR(t[a], -(turnUp - turnDown) / (2 * angle), 5e-3 * t.norm() + 1e-15) << GetParam().name << " torque " << k << a;
    }
  }
}

TEST_P(BondLawSuite, ForcesAndMomentsBalance) {
  Pair pair(GetParam(), {0, 0, 0}, {kL0, 0, 0});
  deform(pair);
  const Eigen::Vector3d fi = pair.force(0), fj = pair.force(1);
  EXPECT_LT((fi + fj).norm(), 1e-12 * fj.norm());
  const Eigen::Vector3d moment = pair.torque(0) + pair.torque(1) + (pair.x(1) - pair.x(0)).cross(fj);
  EXPECT_LT(moment.norm(), 1e-9 * fj.norm() * kL0) << GetParam().name;
}

TEST_P(BondLawSuite, RigidRotationRotatesTheLoadsAndKeepsTheEnergy) {
  Pair pair(GetParam(), {0, 0, 0}, {kL0, 0, 0});
  deform(pair);
  const double energy = pair.energy();
  const Eigen::Vector3d f = pair.force(1), t = pair.torque(1);
  ASSERT_GT(energy, 0);
  // The same bond created along another direction, deformed by the same rotated field.
  const Eigen::Quaterniond R(Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 2, -0.5).normalized()));
  Pair turned(GetParam(), {0, 0, 0}, R * Eigen::Vector3d(kL0, 0, 0));
  // Bonds are created with identity orientations, so the rotated body frames are R q R⁻¹.
  turned.place(0, R * pair.x(0), R * pair.q(0) * R.inverse());
  turned.place(1, R * pair.x(1), R * pair.q(1) * R.inverse());
  EXPECT_NEAR(turned.energy(), energy, 1e-9 * energy) << GetParam().name;
  EXPECT_LT((turned.force(1) - R * f).norm(), 1e-8 * f.norm());
  EXPECT_LT((turned.torque(1) - R * t).norm(), 1e-8 * t.norm() + 1e-20);
}

TEST_P(BondLawSuite, ParticleOrderDoesNotMatter) {
  Pair pair(GetParam(), {0, 0, 0}, {kL0, 0, 0});
  deform(pair);
  // The same two particles stored in the other order: the bond now runs from the other end.
  Pair swapped(GetParam(), {kL0, 0, 0}, {0, 0, 0});
  swapped.place(0, pair.x(1), pair.q(1));
  swapped.place(1, pair.x(0), pair.q(0));
  ASSERT_LT(swapped.s.bonds.n0x[0], 0);  // the bond's reference direction is reversed
  const double energy = pair.energy();
  EXPECT_NEAR(swapped.energy(), energy, 1e-9 * energy) << GetParam().name;
  EXPECT_LT((swapped.force(0) - pair.force(1)).norm(), 1e-9 * pair.force(1).norm());
  EXPECT_LT((swapped.torque(0) - pair.torque(1)).norm(), 1e-9 * pair.torque(1).norm() + 1e-20);
}

INSTANTIATE_TEST_SUITE_P(EveryStyle, BondLawSuite, ::testing::ValuesIn(everyStyle()),
                         [](const auto& info) { return info.param.name; });

// --- Rejected parameters name the field (one spec per model, through the scenario validator) ---

nlohmann::json latticeSpec(const std::string& lattice, int dimension, const nlohmann::json& material) {
  nlohmann::json size = dimension == 2 ? nlohmann::json{2e-3, 1e-3} : nlohmann::json{2e-3, 1e-3, 1e-3};
  return {{"scenario", "dynamic-tension"},
          {"dimension", dimension},
          {"sample", {{"lattice", lattice}, {"size", size}, {"spacing", 1e-4}}},
          {"material", material},
          {"loading", {{"strain_rate", 100}, {"initial_velocity", "VL"}}}};
}

TEST(BondLawSpecs, ValidSpecsOfEveryModelPass) {
  using testing::rejectedField;
  EXPECT_EQ(rejectedField(latticeSpec("triangular", 2, {{"model", "hookean"}, {"density", 2500}, {"hookean", {{"young_modulus", 70e9}}}})), "");
  EXPECT_EQ(rejectedField(latticeSpec("fcc", 3, {{"model", "born"}, {"density", 2500}, {"born", {{"young_modulus", 70e9}, {"poisson_ratio", 0.2}, {"criterion", "griffith"}, {"fracture_energy", 10}}}})), "");
  EXPECT_EQ(rejectedField(latticeSpec("simple-cubic", 3, {{"model", "pmb"}, {"density", 2500}, {"pmb", {{"young_modulus", 70e9}, {"fracture_energy", 10}}}})), "");
}

TEST(BondLawSpecs, RejectedParametersNameTheField) {
  using testing::rejectedField;
  auto hookean = [](nlohmann::json block) { return nlohmann::json{{"model", "hookean"}, {"density", 2500}, {"hookean", block}}; };
  auto born = [](nlohmann::json block) { return nlohmann::json{{"model", "born"}, {"density", 2500}, {"born", block}}; };
  auto pmb = [](nlohmann::json block) { return nlohmann::json{{"model", "pmb"}, {"density", 2500}, {"pmb", block}}; };
  // Poisson ratio outside what the model reaches on that lattice.
  EXPECT_EQ(rejectedField(latticeSpec("triangular", 2, born({{"young_modulus", 70e9}, {"poisson_ratio", 0.4}}))), "material.born.poisson_ratio");
  EXPECT_EQ(rejectedField(latticeSpec("simple-cubic", 3, born({{"young_modulus", 70e9}, {"poisson_ratio", 0.3}}))), "material.born.poisson_ratio");
  EXPECT_EQ(rejectedField(latticeSpec("square", 2, born({{"young_modulus", 70e9}, {"poisson_ratio", -1.0}}))), "material.born.poisson_ratio");
  EXPECT_EQ(rejectedField(latticeSpec("square", 2, hookean({{"young_modulus", 70e9}, {"poisson_ratio", 0.25}}))), "material.hookean.poisson_ratio");
  EXPECT_EQ(rejectedField(latticeSpec("square", 2, hookean({{"young_modulus", -1.0}}))), "material.hookean.young_modulus");
  EXPECT_EQ(rejectedField(latticeSpec("square", 2, hookean({{"young_modulus", 70e9}, {"criterion", "rankine"}}))), "material.hookean.criterion");
  EXPECT_EQ(rejectedField(latticeSpec("square", 2, hookean({{"young_modulus", 70e9}, {"criterion", "griffith"}, {"critical_stretch", 0.01}}))), "material.hookean.critical_stretch");
  EXPECT_EQ(rejectedField(latticeSpec("square", 2, pmb({{"young_modulus", 70e9}, {"horizon_factor", 0.5}}))), "material.pmb.horizon_factor");
  EXPECT_EQ(rejectedField(latticeSpec("square", 2, pmb({{"young_modulus", 70e9}, {"critical_stretch", 1e-3}, {"fracture_energy", 5}}))), "material.pmb.fracture_energy");
  EXPECT_EQ(rejectedField(latticeSpec("square", 2, pmb({{"young_modulus", 70e9}, {"criterion", "critical_energy"}}))), "material.pmb.fracture_energy");
  // Interblock critical stretches: only with the critical-stretch criterion, keys "a_b".
  nlohmann::json blocks = latticeSpec("square", 2, pmb({{"young_modulus", 70e9}, {"critical_stretch", 1e-3}}));
  blocks["sample"]["blocks"] = {{{"id", 2}, {"min", {1e-3, 0.0}}, {"max", {2e-3, 1e-3}}}};
  blocks["material"]["interblock"] = {{"1_2", 1e-4}, {"2_1", 2e-4}};
  EXPECT_EQ(rejectedField(blocks), "");
  blocks["material"]["interblock"] = {{"1-2", 1e-4}};
  EXPECT_EQ(rejectedField(blocks), "material.interblock.1-2");
  blocks["material"]["interblock"] = {{"1_2", -1.0}};
  EXPECT_EQ(rejectedField(blocks), "material.interblock.1_2");
  nlohmann::json griffith = latticeSpec("square", 2, hookean({{"young_modulus", 70e9}, {"criterion", "griffith"}, {"fracture_energy", 1.0}}));
  griffith["material"]["interblock"] = {{"1_2", 1e-4}};
  EXPECT_EQ(rejectedField(griffith), "material.interblock");
  // A model on a sample it does not support, a lattice of the wrong dimension.
  EXPECT_EQ(rejectedField(latticeSpec("triangular", 2, pmb({{"young_modulus", 70e9}}))), "material.model");
  EXPECT_EQ(rejectedField(latticeSpec("fcc", 2, hookean({{"young_modulus", 70e9}}))), "sample.lattice");
  nlohmann::json random = latticeSpec("square", 2, hookean({{"young_modulus", 70e9}}));
  random["sample"] = {{"size", {2e-3, 1e-3}}, {"element_radius", 5e-5}};
  EXPECT_EQ(rejectedField(random), "material.model");
}

}  // namespace
}  // namespace rupture
