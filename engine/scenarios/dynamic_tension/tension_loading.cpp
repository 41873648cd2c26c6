#include "scenarios/dynamic_tension/tension_loading.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace rupture {

TensionGeometry tensionGeometry(const BondedSystem& system, const SampleSpec& sample,
                                const SampleReport& report) {
  const ParticleStore& p = system.particles;
  const std::size_t n = p.size();
  if (n == 0) throw std::runtime_error("dynamic-tension: the sample has no element");
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (std::size_t k = 0; k < n; ++k) {
    low = std::min(low, p.x[k] - p.radius[k]);
    high = std::max(high, p.x[k] + p.radius[k]);
  }
  const double band = 0.5 * sample.elementRadius;
  TensionGeometry g;
  for (std::size_t k = 0; k < n; ++k) {
    const bool atMin = p.x[k] - p.radius[k] <= low + band;
    const bool atMax = p.x[k] + p.radius[k] >= high - band;
    if (atMin && atMax)
      throw std::runtime_error("dynamic-tension: an element touches both X faces; sample.size[0] is too small");
    if (atMin) { g.xmin.push_back(static_cast<std::int32_t>(k)); g.xminCentre += p.x[k]; }
    if (atMax) { g.xmax.push_back(static_cast<std::int32_t>(k)); g.xmaxCentre += p.x[k]; }
  }
  if (g.xmin.empty() || g.xmax.empty())
    throw std::runtime_error("dynamic-tension: a loaded face (X_min or X_max) has no element");
  g.xminCentre /= static_cast<double>(g.xmin.size());
  g.xmaxCentre /= static_cast<double>(g.xmax.size());
  g.gaugeLength = g.xmaxCentre - g.xminCentre;

  // Eq. 4: S = L × R_DE in 2D (the builder's thickness t = R_DE), the face area in 3D.
  if (sample.dimension == 2) {
    g.section = sample.size[1] * report.thickness;
    g.volume = sample.size[0] * sample.size[1] * report.thickness;
  } else {
    g.section = sample.size[1] * sample.size[2];
    g.volume = sample.size[0] * sample.size[1] * sample.size[2];
  }
  double mass = 0;
  for (double m : p.mass) mass += m;
  g.bulkDensity = mass / g.volume;
  return g;
}

double VelocityRamp::velocity(double t) const {
  if (t >= rampTime) return maxVelocity;
  if (t <= 0) return 0.0;
  return maxVelocity * 0.5 * (1.0 - std::cos(std::numbers::pi * t / rampTime));
}

double VelocityRamp::displacement(double t) const {
  if (t <= 0) return 0.0;
  if (t >= rampTime) return maxVelocity * (t - 0.5 * rampTime);
  const double w = std::numbers::pi / rampTime;
  return 0.5 * maxVelocity * (t - std::sin(w * t) / w);
}

double VelocityRamp::timeToReach(double u) const {
  if (!(u > 0) || !(maxVelocity > 0)) return 0.0;
  if (u >= 0.5 * maxVelocity * rampTime) return u / maxVelocity + 0.5 * rampTime;
  double lo = 0, hi = rampTime;  // displacement() is increasing: bisection
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (displacement(mid) < u ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TensionLoading::TensionLoading(TensionGeometry geometry, double strainRate, double rampTime)
    : m_geometry(std::move(geometry)), m_strainRate(strainRate) {
  m_ramp.maxVelocity = strainRate * m_geometry.gaugeLength;  // eq. 3: V_max = ε̇ L0
  m_ramp.rampTime = rampTime;
  m_probe = m_geometry.xmax.front();
}

void TensionLoading::install(BondedSystem& system) {
  setReference(system.particles);
  prescribeFaces(system, m_geometry.xmin, m_geometry.xmax);
}

void TensionLoading::setReference(const ParticleStore& reference) { m_probeX0 = reference.x[m_probe]; }

void TensionLoading::prescribeFaces(BondedSystem& system, std::vector<std::int32_t> xmin,
                                    std::vector<std::int32_t> xmax) const {
  ParticleStore& p = system.particles;
  for (std::int32_t k : xmin) p.fixedDofs[k] |= kFixX;
  for (std::int32_t k : xmax) p.fixedDofs[k] |= kFixX;
  // The callback owns copies: it must outlive neither this object nor the caller's scope.
  system.prescribe = [xmin = std::move(xmin), xmax = std::move(xmax), ramp = m_ramp](ParticleStore& s, double t) {
    const double v = ramp.velocity(t);
    for (std::int32_t k : xmin) s.vx[k] = 0.0;  // U_x = 0 on X_min
    for (std::int32_t k : xmax) s.vx[k] = v;    // V_x(t) on X_max
  };
  system.prescribe(p, system.time);
}

FaceStresses TensionLoading::stresses(const ParticleStore& p) const {
  double fMin = 0, fMax = 0;
  for (std::int32_t k : m_geometry.xmin) fMin += p.fx[k];
  for (std::int32_t k : m_geometry.xmax) fMax += p.fx[k];
  return stressesFrom(fMin, fMax);
}

FaceStresses TensionLoading::stressesFrom(double fMin, double fMax) const {
  FaceStresses s;
  s.xmin = fMin / m_geometry.section;
  s.xmax = -fMax / m_geometry.section;
  s.mean = 0.5 * (s.xmin + s.xmax);
  return s;
}

double affineWaveSpeed(const BondedSystem& system, const TensionGeometry& geometry) {
  const BondStore& bonds = system.bonds;
  const std::vector<double> stiffness = system.bondStiffness();
  double modulus = 0;
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    if (bonds.intact[b] <= 0.0) continue;
    const double L0 = bonds.restLength[b];
    const double k = stiffness[b];
    const double nx2 = bonds.n0x[b] * bonds.n0x[b];
    modulus += k * L0 * L0 * nx2 * nx2;
  }
  modulus /= geometry.volume;
  return std::sqrt(modulus / geometry.bulkDensity);
}

}  // namespace rupture
