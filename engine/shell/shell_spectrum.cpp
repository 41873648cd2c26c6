// The largest frequency of the SPH shell's discrete operator, measured rather than bounded.
//
// The step estimate of SphShell's constructor bounds the corrected-kernel operator by a wave
// number k = 2.5/Δ and, where the thickness steps, by the thick stress points' stiffness against
// the thin node's mass. Both are bounds, not the operator's spectrum: the kernel's support spans
// 2.6 Δ, so the gradients filter the shortest waves, and a thin node beside a thick stress point
// sits where that point's kernel gradient is weak. The central difference is stable when
// ω_max dt ≤ 2 with ω_max the largest frequency of the linearised system M⁻¹K (Belytschko, Liu &
// Moran, Nonlinear Finite Elements, 2000, ch. 6). It is measured here by power iteration, K applied
// by differences of the internal forces about the current state, with the layers elastic (the
// tangent of a layer that yields or softens is smaller, so its frequencies are not higher).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "shell/sph_shell.hpp"
#include "shell/shell_vector.hpp"

namespace rupture {
namespace {

/// A vector of the shell's free degrees of freedom: a translation u_i (m) and a director rotation
/// θ_i (rad, perpendicular to n_i) per node.
struct Motion {
  std::vector<ShellVec3> u, theta;
};

}  // namespace

double SphShell::maxFrequency(const std::vector<std::uint8_t>& pointTerm, const std::vector<std::uint8_t>& nodeTerm,
                              int iterations) {
  const std::size_t n = m_position.size();
  if (pointTerm.size() != n || nodeTerm.size() != n || iterations < 1)
    throw std::invalid_argument("SphShell::maxFrequency: one flag per node and at least one iteration");

  // The terms to probe as class 0 of a two-class plan (the others as class 1, which computeForces
  // at firing 0 leaves out): a stress point by its flag; an hourglass pair fires when either node
  // is flagged (the finer of its nodes' classes), which can only add stiffness.
  std::vector<double> nodeStep(n), pointStep(n);
  for (std::size_t i = 0; i < n; ++i) {
    nodeStep[i] = nodeTerm[i] ? 1.0 : 2.0;
    pointStep[i] = pointTerm[i] ? 1.0 : 2.0;
  }
  ShellStepClasses probe;
  probe.assign(nodeStep, pointStep, SubcyclingPlan{2, 1, 1.0}, m_offset, m_neighbour);

  // What computeForces writes, put back at the end: the next step starts from the same state.
  const auto position = m_position, normal = m_normal;
  const auto gradX = m_gradX, gradN = m_gradN;
  const auto stressP = m_stressP, stressR = m_stressR;
  const auto shearQ = m_shearQ;
  const auto moment = m_moment;
  const auto pointStrain = m_pointStrain;
  const auto force = m_force;
  const auto directorForce = m_directorForce;
  const double pressure = m_pressure;
  const std::uint64_t evaluations = m_pointEvaluations;
  const Timings timings = m_timings;
  ShellStepClasses classes = std::move(m_classes);
  m_classes = std::move(probe);
  m_elasticProbe = true;
  m_pressure = 0.0;  // a follower load's stiffness is not the structure's

  auto forcesAt = [&](const Motion* v, double eps) {
    for (std::size_t i = 0; i < n; ++i) {
      m_position[i] = position[i];
      m_normal[i] = normal[i];
      if (!v) continue;
      const ShellVec3 turn = cross(v->theta[i], normal[i]);
      double len = 0.0;
      for (int a = 0; a < 3; ++a) {
        m_position[i][a] += eps * v->u[i][a];
        m_normal[i][a] += eps * turn[a];
        len += m_normal[i][a] * m_normal[i][a];
      }
      len = std::sqrt(len);
      for (int a = 0; a < 3; ++a) m_normal[i][a] /= len;
    }
    computeForces(0.0, 0);
  };
  // The generalised forces of the current state: force on the translation, torque n × g on the
  // rotation (without its drilling part).
  auto generalised = [&](Motion& out) {
    out.u.assign(n, {0.0, 0.0, 0.0});
    out.theta.assign(n, {0.0, 0.0, 0.0});
    for (std::size_t i = 0; i < n; ++i) {
      if (m_clamped[i]) continue;
      out.u[i] = m_force[i];
      ShellVec3 torque = cross(m_normal[i], m_directorForce[i]);
      const double along = dot(torque, normal[i]);
      for (int a = 0; a < 3; ++a) torque[a] -= along * normal[i][a];
      out.theta[i] = torque;
    }
  };
  auto massNorm = [&](const Motion& v) {
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      if (!m_clamped[i]) sum += m_mass[i] * dot(v.u[i], v.u[i]) + m_inertia[i] * dot(v.theta[i], v.theta[i]);
    return std::sqrt(sum);
  };

  Motion f0, f1, v;
  forcesAt(nullptr, 0.0);
  generalised(f0);
  // A deterministic start with a component along every degree of freedom.
  std::mt19937_64 random(20261206);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  v.u.assign(n, {0.0, 0.0, 0.0});
  v.theta.assign(n, {0.0, 0.0, 0.0});
  for (std::size_t i = 0; i < n; ++i) {
    if (m_clamped[i]) continue;
    for (int a = 0; a < 3; ++a) v.u[i][a] = uniform(random) / std::sqrt(m_mass[i]);
    ShellVec3 r = {uniform(random), uniform(random), uniform(random)};
    const double along = dot(r, normal[i]);
    for (int a = 0; a < 3; ++a) v.theta[i][a] = (r[a] - along * normal[i][a]) / std::sqrt(m_inertia[i]);
  }
  const double spacing = *std::min_element(m_nodeSpacing.begin(), m_nodeSpacing.end());
  double omega2 = 0.0;
  for (int it = 0; it < iterations; ++it) {
    const double norm = massNorm(v);
    if (!(norm > 0.0)) break;
    double largest = 0.0, turn = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      for (int a = 0; a < 3; ++a) v.u[i][a] /= norm, v.theta[i][a] /= norm;
      largest = std::max(largest, std::sqrt(dot(v.u[i], v.u[i])));
      turn = std::max(turn, std::sqrt(dot(v.theta[i], v.theta[i])));
    }
    // A perturbation of 1e-7 of the finest spacing (and 1e-7 rad): linear to round-off, well above it.
    const double eps = 1e-7 * std::min(largest > 0.0 ? spacing / largest : 1e300, turn > 0.0 ? 1.0 / turn : 1e300);
    forcesAt(&v, eps);
    generalised(f1);
    // w = −M⁻¹ (F(x + ε v) − F(x)) / ε; ‖w‖_M / ‖v‖_M ≤ ω_max² for the symmetric K, and tends to it.
    for (std::size_t i = 0; i < n; ++i) {
      if (m_clamped[i]) continue;
      for (int a = 0; a < 3; ++a) {
        v.u[i][a] = -(f1.u[i][a] - f0.u[i][a]) / (eps * m_mass[i]);
        v.theta[i][a] = -(f1.theta[i][a] - f0.theta[i][a]) / (eps * m_inertia[i]);
      }
    }
    omega2 = std::max(omega2, massNorm(v));
  }

  m_position = position;
  m_normal = normal;
  m_gradX = gradX;
  m_gradN = gradN;
  m_stressP = stressP;
  m_stressR = stressR;
  m_shearQ = shearQ;
  m_moment = moment;
  m_pointStrain = pointStrain;
  m_force = force;
  m_directorForce = directorForce;
  m_pressure = pressure;
  m_pointEvaluations = evaluations;
  m_timings = timings;
  m_classes = std::move(classes);
  m_elasticProbe = false;
  return std::sqrt(omega2);
}

void SphShell::measureOwnSteps() {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = m_position.size();
  // Groups: the bound's classes about its single-rate step, g = ⌊log2(h_j / h_min)⌋ (at most
  // 2^kMaxStepClass apart, as the classes): the bound orders the terms by stiffness well, it is
  // its scale that is far off (5.8 times on the seed's TF14A5 plate, docs/shell-and-damage.md).
  // The single rate needs only the largest frequency of them all: one group, the whole operator
  // (a measurement of 13,034 points per iteration on that plate instead of 30,800 over its four).
  auto groupOf = [&](double h) {
    int g = 0;
    while (m_params.subcycling && g < kMaxStepClass && std::ldexp(m_boundStableStep, g + 1) <= h) ++g;
    return g;
  };
  std::vector<int> pointGroup(n), nodeGroup(n, kMaxStepClass);
  for (std::size_t j = 0; j < n; ++j) pointGroup[j] = groupOf(m_boundPointStep[j]);
  // A node's group: the finest of the points that reach it (its own and its kernel's), as its step.
  for (std::size_t i = 0; i < n; ++i) {
    if (m_clamped[i]) continue;
    int g = pointGroup[i];
    for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) g = std::min(g, pointGroup[m_neighbour[p]]);
    nodeGroup[i] = g;
  }
  // ω_g: the largest frequency of the terms of group g and coarser (group g fires with them, every
  // 2^c fine steps of its class or more often), from the coarsest group to the finest, each at
  // least the next coarser one's (a larger set of terms is no softer; the power iteration can fall
  // short of the top of a spectrum, never above it).
  std::vector<double> frequency(kMaxStepClass + 1, 0.0);
  std::vector<std::uint8_t> present(kMaxStepClass + 1, 0);
  for (int g : pointGroup) present[static_cast<std::size_t>(g)] = 1;
  double coarser = 0.0;
  std::vector<std::uint8_t> pointTerm(n), nodeTerm(n);
  for (int g = kMaxStepClass; g >= 0; --g) {
    if (!present[static_cast<std::size_t>(g)]) continue;
    for (std::size_t i = 0; i < n; ++i) {
      pointTerm[i] = pointGroup[i] >= g;
      nodeTerm[i] = nodeGroup[i] >= g;
    }
    coarser = std::max(coarser, maxFrequency(pointTerm, nodeTerm, kSpectrumIterations));
    frequency[static_cast<std::size_t>(g)] = coarser;
  }
  // A group's step is C · 2/ω_g (the bound's, where its terms have no stiffness left to measure).
  const double never = std::numeric_limits<double>::infinity();
  std::vector<double> groupStep(kMaxStepClass + 1, never);
  m_groupFrequency.clear();
  for (int g = 0; g <= kMaxStepClass; ++g) {
    if (!present[static_cast<std::size_t>(g)]) continue;
    const double w = frequency[static_cast<std::size_t>(g)];
    groupStep[static_cast<std::size_t>(g)] =
        w > 0.0 ? m_params.courantFactor * 2.0 / w : std::ldexp(m_boundStableStep, g);
    m_groupFrequency.push_back(w);
  }
  m_stableStep = never;
  for (std::size_t j = 0; j < n; ++j) {
    m_pointStep[j] = groupStep[static_cast<std::size_t>(pointGroup[j])];
    m_stableStep = std::min(m_stableStep, m_pointStep[j]);
  }
  for (std::size_t i = 0; i < n; ++i)
    m_ownStep[i] = m_clamped[i] ? never : groupStep[static_cast<std::size_t>(nodeGroup[i])];
  m_rebuiltSinceMeasure = 0;
  ++m_spectrumMeasurements;
  m_timings.spectrum += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rupture
