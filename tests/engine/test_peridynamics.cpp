// PMB peridynamics (peridynamics/pmb.hpp) on built lattice samples: the micromodulus gives the
// target bulk modulus away from surfaces, a plane wave travels at the continuum speed, and the
// critical stretch (or critical energy) derived from G0 costs G0 per unit area to cut every bond
// across a plane, in 2D and 3D.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "samples/sample_builder.hpp"
#include "peridynamics/pmb.hpp"

namespace rupture {
namespace {

constexpr double kPdSpacing = 1e-3, kPdYoung = 72e9, kDensity = 2200, kHorizonFactor = 3.015;

SampleSpec pdSample(int dimension, std::array<int, 3> sites) {
  SampleSpec s;
  s.dimension = dimension;
  s.lattice = dimension == 2 ? "square" : "simple-cubic";
  s.spacing = kPdSpacing;
  s.elementRadius = 0.5 * kPdSpacing;
  s.thickness = dimension == 2 ? kPdSpacing : 0.0;
  s.size = {sites[0] * kPdSpacing, sites[1] * kPdSpacing, dimension == 3 ? sites[2] * kPdSpacing : 0.0};
  return s;
}

MaterialSpec pmbMaterial(double fractureEnergy, const std::string& criterion = "critical_stretch") {
  MaterialSpec m;
  m.model = "pmb";
  m.density = kDensity;
  m.pmb.youngModulus = kPdYoung;
  m.pmb.horizonFactor = kHorizonFactor;
  m.pmb.fractureEnergy = fractureEnergy;
  m.pmb.criterion = criterion;
  m.contact.enabled = false;
  return m;
}

/// Sites at least `margin` inside every face of the sample.
std::vector<std::uint8_t> interior(const ParticleStore& p, double margin) {
  double lo[3], hi[3];
  const std::vector<double>* c[3] = {&p.x, &p.y, &p.z};
  for (int a = 0; a < 3; ++a) {
    lo[a] = *std::min_element(c[a]->begin(), c[a]->end());
    hi[a] = *std::max_element(c[a]->begin(), c[a]->end());
  }
  std::vector<std::uint8_t> in(p.size(), 1);
  for (std::size_t k = 0; k < p.size(); ++k)
    for (int a = 0; a < p.dimension; ++a)
      if ((*c[a])[k] < lo[a] + margin || (*c[a])[k] > hi[a] - margin) in[k] = 0;
  return in;
}

TEST(Pmb, IsotropicStretchGivesTheTargetBulkModulusAwayFromSurfaces) {
  BondedSystem s;
  buildSample(pdSample(3, {16, 16, 16}), pmbMaterial(NAN), s);
  const double eps = 1e-4, delta = kHorizonFactor * kPdSpacing;
  const std::vector<std::uint8_t> in = interior(s.particles, delta + kPdSpacing);
  ParticleStore& p = s.particles;
  for (std::size_t k = 0; k < p.size(); ++k) { p.x[k] *= 1 + eps; p.y[k] *= 1 + eps; p.z[k] *= 1 + eps; }
  // Each site owns half the energy of each of its bonds: W_i V_i = ½ Σ_j U_ij.
  double energy = 0, volume = 0;
  for (std::size_t b = 0; b < s.bonds.size(); ++b) {
    const double L0 = s.bonds.restLength[b], dL = eps * L0;
    energy += 0.5 * (in[s.bonds.i[b]] + in[s.bonds.j[b]]) * 0.5 * s.bonds.stiffness[b] * dL * dL;
  }
  std::size_t count = 0;
  for (std::size_t k = 0; k < p.size(); ++k) if (in[k]) { volume += p.volume[k]; ++count; }
  ASSERT_GT(count, 100u);
  const double bulk = 2.0 * (energy / volume) / (9.0 * eps * eps);  // W = 9/2 K ε²
  EXPECT_NEAR(bulk, pmbBulkModulus(kPdYoung), 0.03 * pmbBulkModulus(kPdYoung));
}

TEST(Pmb, APlaneWaveTravelsAtTheContinuumSpeed) {
  // A 2D strip held in y (uniaxial strain): the front of a smooth velocity step imposed on the
  // left layer reaches two stations of the centre row; c = Δx / Δt against √(C11/ρ),
  // C11 = E / (1 − ν²) in plane stress with ν = 1/3.
  BondedSystem s;
  buildSample(pdSample(2, {200, 16, 0}), pmbMaterial(NAN), s);
  ParticleStore& p = s.particles;
  const double v0 = 0.1, delta = kHorizonFactor * kPdSpacing;
  const double c = std::sqrt(kPdYoung / (1.0 - 1.0 / 9.0) / kDensity);
  const double rise = 10 * kPdSpacing / c;
  const double yMid = 0.5 * (*std::min_element(p.y.begin(), p.y.end()) + *std::max_element(p.y.begin(), p.y.end()));
  std::vector<std::size_t> driven;
  std::size_t stationA = 0, stationB = 0;
  const double xa = 60 * kPdSpacing, xb = 140 * kPdSpacing;
  for (std::size_t k = 0; k < p.size(); ++k) {
    p.fixedDofs[k] = kFixY | kFixZ;
    if (p.x[k] < delta) { driven.push_back(k); p.fixedDofs[k] |= kFixX; }
    if (std::fabs(p.y[k] - yMid) < 0.6 * kPdSpacing) {
      if (std::fabs(p.x[k] - xa) < std::fabs(p.x[stationA] - xa) || std::fabs(p.y[stationA] - yMid) >= 0.6 * kPdSpacing) stationA = k;
      if (std::fabs(p.x[k] - xb) < std::fabs(p.x[stationB] - xb) || std::fabs(p.y[stationB] - yMid) >= 0.6 * kPdSpacing) stationB = k;
    }
  }
  s.prescribe = [&](ParticleStore& ps, double t) {
    const double v = t < rise ? v0 * 0.5 * (1 - std::cos(std::numbers::pi * t / rise)) : v0;
    for (std::size_t k : driven) ps.vx[k] = v;
  };
  const double dt = 0.5 * s.criticalTimeStep();
  double arrivalA = -1, arrivalB = -1, previousA = 0, previousB = 0;
  while (arrivalB < 0 && s.time < 3 * (xb / c)) {
    s.step(dt);
    // Linear interpolation of the time the velocity crosses v0/2.
    const double va = p.vx[stationA], vb = p.vx[stationB];
    if (arrivalA < 0 && va >= 0.5 * v0) arrivalA = s.time - dt * (va - 0.5 * v0) / (va - previousA);
    if (arrivalB < 0 && vb >= 0.5 * v0) arrivalB = s.time - dt * (vb - 0.5 * v0) / (vb - previousB);
    previousA = va;
    previousB = vb;
  }
  ASSERT_GT(arrivalA, 0);
  ASSERT_GT(arrivalB, 0);
  const double speed = (p.x[stationB] - p.x[stationA]) / (arrivalB - arrivalA);
  EXPECT_NEAR(speed, c, 0.05 * c);
}

/// Energy per unit area to break every bond crossing the mid-plane x = x_c. Each crossing bond is
/// counted on its site left of the plane; only sites at least δ + l inside the lateral faces count,
/// and the area is their number of rows (and layers) times the spacing (times the thickness in 2D).
double cutEnergyPerArea(const BondedSystem& s, const SampleSpec& spec, bool byThreshold, double s0) {
  const ParticleStore& p = s.particles;
  const double delta = kHorizonFactor * kPdSpacing, margin = delta + kPdSpacing;
  const auto [xlo, xhi] = std::minmax_element(p.x.begin(), p.x.end());
  const double xc = 0.5 * (*xlo + *xhi) + 0.25 * kPdSpacing;  // between two site planes whatever the parity
  const auto [ylo, yhi] = std::minmax_element(p.y.begin(), p.y.end());
  const auto [zlo, zhi] = std::minmax_element(p.z.begin(), p.z.end());
  auto inBand = [&](double v, double lo, double hi) { return v >= lo + margin && v <= hi - margin; };
  auto rows = [&](double lo, double hi) {  // sites per line inside the band
    return std::floor((hi - margin) / kPdSpacing - 0.5) - std::ceil((lo + margin) / kPdSpacing - 0.5) + 1;
  };
  double energy = 0;
  for (std::size_t b = 0; b < s.bonds.size(); ++b) {
    const std::int32_t i = s.bonds.i[b], j = s.bonds.j[b];
    if ((p.x[i] - xc) * (p.x[j] - xc) >= 0) continue;
    const std::int32_t left = p.x[i] < xc ? i : j;
    if (!inBand(p.y[left], *ylo, *yhi) || (spec.dimension == 3 && !inBand(p.z[left], *zlo, *zhi))) continue;
    const double L0 = s.bonds.restLength[b];
    energy += byThreshold ? s.bonds.threshold[b] : 0.5 * s.bonds.stiffness[b] * (s0 * L0) * (s0 * L0);
  }
  const double area = spec.dimension == 2 ? rows(*ylo, *yhi) * kPdSpacing * spec.thickness
                                          : rows(*ylo, *yhi) * rows(*zlo, *zhi) * kPdSpacing * kPdSpacing;
  return energy / area;
}

TEST(Pmb, CriticalStretchFromG0CostsG0PerUnitAreaIn2DAnd3D) {
  const double G0 = 8.0;  // J/m²
  for (int d : {2, 3}) {
    const SampleSpec spec = d == 2 ? pdSample(2, {30, 40, 0}) : pdSample(3, {14, 20, 20});
    BondedSystem s;
    buildSample(spec, pmbMaterial(G0), s);
    const double s0 = pmbCriticalStretch(d, kPdYoung, kHorizonFactor * kPdSpacing, G0);
    EXPECT_DOUBLE_EQ(s.bonds.threshold[0], s0);
    EXPECT_NEAR(cutEnergyPerArea(s, spec, false, s0), G0, 0.05 * G0) << d << "D";
    // The critical-energy criterion's thresholds are the same cut energy.
    BondedSystem e;
    buildSample(spec, pmbMaterial(G0, "critical_energy"), e);
    EXPECT_NEAR(cutEnergyPerArea(e, spec, true, 0.0), G0, 0.05 * G0) << d << "D critical energy";
  }
}

TEST(Pmb, MicromodulusAndCriticalValuesMatchTheReferenceFormulas) {
  const double delta = 1.5e-3, K = 14.9e9, E = 1.5 * K;
  // LAMMPS's examples/peri value: c = 1.6863e22 for K = 14.9 GPa, δ = 1.5 mm (docs/references.md#eq-pd).
  EXPECT_NEAR(pmbMicromodulus(3, E, delta, 0.0), 1.6863e22, 1e-4 * 1.6863e22);
  const double t = 2e-3;
  EXPECT_NEAR(pmbMicromodulus(2, E, delta, t), 9 * E / (std::numbers::pi * t * std::pow(delta, 3)), 1);
  // s0 and the G0 identities of §3.3: G0 = π c s0² δ⁵ / 10 (3D), G0 = c s0² t δ⁴ / 4 (2D).
  const double G0 = 3.0;
  const double s3 = pmbCriticalStretch(3, E, delta, G0), c3 = pmbMicromodulus(3, E, delta, 0);
  EXPECT_NEAR(std::numbers::pi * c3 * s3 * s3 * std::pow(delta, 5) / 10, G0, 1e-9 * G0);
  const double s2 = pmbCriticalStretch(2, E, delta, G0), c2 = pmbMicromodulus(2, E, delta, t);
  EXPECT_NEAR(c2 * s2 * s2 * t * std::pow(delta, 4) / 4, G0, 1e-9 * G0);
}

}  // namespace
}  // namespace rupture
