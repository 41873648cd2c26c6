#include "shell/sph_shell.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "shell/shell_vector.hpp"
#include "shell/wendland_kernel.hpp"

namespace rupture {
namespace {

inline ShellVec3 column(const std::array<double, 6>& m, int alpha) {
  return {m[3 * alpha], m[3 * alpha + 1], m[3 * alpha + 2]};
}

/// Distance from point q to the segment [a, b] in the plane.
double segmentDistance(const std::array<double, 2>& a, const std::array<double, 2>& b,
                       const std::array<double, 2>& q) {
  const double ex = b[0] - a[0], ey = b[1] - a[1];
  const double len2 = ex * ex + ey * ey;
  double s = len2 > 0.0 ? ((q[0] - a[0]) * ex + (q[1] - a[1]) * ey) / len2 : 0.0;
  s = std::clamp(s, 0.0, 1.0);
  const double dx = a[0] + s * ex - q[0], dy = a[1] + s * ey - q[1];
  return std::sqrt(dx * dx + dy * dy);
}

/// The pair quantities of one node's pairs that hang on a square root and a division (|n_i + n_j|,
/// the pair's director n̄), computed ahead of the loop that uses them, all pairs at once: a short
/// loop with no dependence between pairs, which the compiler vectorises, so the latency of the
/// root and the divisions is paid once per vector instead of once per pair on the critical path.
/// The same operations on the same operands: the results are bit for bit those of computing them
/// inside the pair loop.
struct PairDirectors {
  explicit PairDirectors(std::size_t maxPairs) : capacity(maxPairs), values(5 * maxPairs) {}
  double* length() { return values.data(); }                         ///< |n_i + n_j|
  double* mean(int a) { return values.data() + (1 + a) * capacity; }  ///< n̄, component a
  double* shear() { return values.data() + 4 * capacity; }           ///< s_ij (pairShear)
  std::size_t capacity;
  std::vector<double> values;
};

/// |n_i + n_j| and n̄ of node i's pairs first … first + count − 1 (normals: 3 per node).
void pairMeanDirectors(const double* normal, const std::size_t* neighbour, std::size_t i, std::size_t first,
                       std::size_t count, PairDirectors& out) {
  const double ni0 = normal[3 * i], ni1 = normal[3 * i + 1], ni2 = normal[3 * i + 2];
  double *length = out.length(), *m0 = out.mean(0), *m1 = out.mean(1), *m2 = out.mean(2);
#pragma omp simd
  for (std::size_t l = 0; l < count; ++l) {
    const std::size_t j3 = 3 * neighbour[first + l];
    const double s0 = ni0 + normal[j3], s1 = ni1 + normal[j3 + 1], s2 = ni2 + normal[j3 + 2];
    const double len = std::sqrt(s0 * s0 + s1 * s1 + s2 * s2);
    length[l] = len;
    m0[l] = s0 / len;
    m1[l] = s1 / len;
    m2[l] = s2 / len;
  }
}

/// s_ij = (x_j − x_i)·(n_i + n_j)/|n_i + n_j| of node i's pairs (pairShear, all at once).
void pairShears(const double* position, const double* normal, const std::size_t* neighbour, std::size_t i,
                std::size_t first, std::size_t count, PairDirectors& out) {
  const double xi0 = position[3 * i], xi1 = position[3 * i + 1], xi2 = position[3 * i + 2];
  const double ni0 = normal[3 * i], ni1 = normal[3 * i + 1], ni2 = normal[3 * i + 2];
  double* shear = out.shear();
#pragma omp simd
  for (std::size_t l = 0; l < count; ++l) {
    const std::size_t j3 = 3 * neighbour[first + l];
    const double m0 = ni0 + normal[j3], m1 = ni1 + normal[j3 + 1], m2 = ni2 + normal[j3 + 2];
    const double d0 = position[j3] - xi0, d1 = position[j3 + 1] - xi1, d2 = position[j3 + 2] - xi2;
    shear[l] = (d0 * m0 + d1 * m1 + d2 * m2) / std::sqrt(m0 * m0 + m1 * m1 + m2 * m2);
  }
}

/// s_ij = (x_j − x_i)·n̄, n̄ = (n_i + n_j)/|n_i + n_j|: the pair's transverse-shear separation.
inline double pairShear(const ShellVec3& xi, const ShellVec3& xj, const ShellVec3& ni, const ShellVec3& nj) {
  const ShellVec3 m = {ni[0] + nj[0], ni[1] + nj[1], ni[2] + nj[2]};
  const ShellVec3 d = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
  return dot(d, m) / std::sqrt(dot(m, m));
}

}  // namespace

SphShell::SphShell(const ShellNodes& nodes, const ShellParameters& params) : m_params(params) {
  validateShellParameters(m_params, "shell");
  m_params.damageLaw.poissonRatio = m_params.material.poissonRatio;
  const std::size_t n = nodes.size();
  if (n == 0 || nodes.y.size() != n || nodes.kernelVolume.size() != n || nodes.integrationArea.size() != n ||
      nodes.clamped.size() != n)
    throw std::invalid_argument("SphShell: the node arrays must be non-empty and of equal length");
  if (!(nodes.spacing > 0.0)) throw std::invalid_argument("SphShell: the node spacing must be > 0");
  m_spacing = nodes.spacing;
  if (!nodes.nodeSpacing.empty() && nodes.nodeSpacing.size() != n)
    throw std::invalid_argument("SphShell: the node spacings must be absent or one per node");
  m_nodeSpacing = nodes.nodeSpacing.empty() ? std::vector<double>(n, m_spacing) : nodes.nodeSpacing;
  for (double d : m_nodeSpacing)
    if (!(d > 0.0 && d <= m_spacing)) throw std::invalid_argument("SphShell: node spacings must be in (0, spacing]");
  // The rule of the uniform thickness; node i's points and weights are t_i / t times these.
  m_rule = gaussLegendreThickness(m_params.thicknessPoints, m_params.thickness);
  m_layersToFracture = layersToFracture(m_params.fractureLayerFraction, m_params.thicknessPoints);
  const double rho = m_params.density;
  if (!nodes.thickness.empty() && nodes.thickness.size() != n)
    throw std::invalid_argument("SphShell: the node thicknesses must be absent or one per node");
  m_thickness = nodes.thickness.empty() ? std::vector<double>(n, m_params.thickness) : nodes.thickness;
  for (double t : m_thickness)
    if (!(t > 0.0)) throw std::invalid_argument("SphShell: node thicknesses must be > 0");

  m_reference.resize(n);
  m_volume = nodes.kernelVolume;
  m_area = nodes.integrationArea;
  m_clamped = nodes.clamped;
  m_mass.resize(n);
  m_inertia.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    m_reference[i] = {nodes.x[i], nodes.y[i]};
    if (!(m_volume[i] > 0.0) || !(m_area[i] >= 0.0))
      throw std::invalid_argument("SphShell: node volumes must be > 0 and areas >= 0");
    if (!m_clamped[i] && !(m_area[i] > 0.0))
      throw std::invalid_argument("SphShell: a free node needs an integration area > 0");
    const double t = m_thickness[i];
    m_mass[i] = rho * t * m_area[i];
    m_inertia[i] = m_params.rotaryInertiaScale * rho * t * t * t / 12.0 * m_area[i];
  }
  m_position.resize(n);
  for (std::size_t i = 0; i < n; ++i) m_position[i] = {nodes.x[i], nodes.y[i], 0.0};
  m_velocity.assign(n, {0.0, 0.0, 0.0});
  m_normal.assign(n, {0.0, 0.0, 1.0});
  m_spin.assign(n, {0.0, 0.0, 0.0});
  m_force.assign(n, {0.0, 0.0, 0.0});
  m_directorForce.assign(n, {0.0, 0.0, 0.0});
  m_external.assign(n, {0.0, 0.0, 0.0});
  m_gradX.assign(n, {1.0, 0.0, 0.0, 0.0, 1.0, 0.0});
  m_gradN.assign(n, {});
  m_stressP.assign(n, {});
  m_stressR.assign(n, {});
  m_shearQ.assign(n, {0.0, 0.0});
  m_moment.assign(n, {0.0, 0.0, 0.0});
  m_fractured.assign(n, 0);
  m_fractureTime.assign(n, std::numeric_limits<double>::quiet_NaN());
  m_hasGradient.assign(n, 0);
  const std::size_t layers = m_rule.xi.size();
  m_plasticStrainTensor.assign(n * layers, {0.0, 0.0, 0.0});
  m_plasticStrain.assign(n * layers, 0.0);
  m_plasticShear.assign(n * layers, {0.0, 0.0});
  m_damage.assign(n * layers, DamageState{});

  buildNeighbours();
  buildCorrections();

  const ElasticPlasticMaterial& m = m_params.material;
  const double nu = m.poissonRatio;
  const double cp2 = m.youngModulus / (rho * (1.0 - nu * nu));
  const double k = 2.5 / *std::min_element(m_nodeSpacing.begin(), m_nodeSpacing.end());  // the finest nodes
  const double shearModulus = m_params.shearCorrection * m.shearModulus();  // κ_s G

  // Where the thickness steps, a node's motion strains the stress points of thicker neighbours
  // (their kernels reach it): its translation sees their stiffness E t_j against its own mass
  // ρ t_i, which raises the translation's ω by √(t_j / t_i); its rotation sees their bending
  // stiffness ∝ t_j³ against its rotary inertia ρ t_i³/12, which would raise the rotation's ω by
  // (t_j / t_i)^{3/2} (125 for the seed's 1 mm spot face in its 25 mm bottom). Rotary-inertia
  // scaling on these nodes only: I = f ρ t_i t_j²/12, f = stepRotaryInertia, the least inertia
  // (f = 1) whose rotation is no faster than the translation, so the step stays the
  // translation's. The static solution and the translational inertia are unchanged; a larger
  // inertia slows the hinge that forms at the step (TF14A5 tears 0.44 ms later with ρ t_j³/12).
  double stiffnessRatio = 1.0, stepRotation2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double ti = m_thickness[i];
    double thickest = ti;
    for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) thickest = std::max(thickest, m_thickness[m_neighbour[p]]);
    if (thickest > ti) {
      const double inertia = std::max(ti * ti * ti, m_params.stepRotaryInertia * ti * thickest * thickest);  // × ρ/12
      m_inertia[i] = m_params.rotaryInertiaScale * rho * inertia / 12.0 * m_area[i];
      if (!m_clamped[i]) {
        stiffnessRatio = std::max(stiffnessRatio, thickest / ti);
        // The thick stress points' bending D_j k² and shear κ_s G t_j against this node's inertia.
        const double stiffness = cp2 * k * k * thickest * thickest * thickest + 12.0 * shearModulus * thickest / rho;
        stepRotation2 = std::max(stepRotation2, stiffness / (m_params.rotaryInertiaScale * inertia));
      }
    }
  }

  // Hourglass stiffnesses of each node's thickness (membrane α E t, bending α E t³/(12(1 − ν²)),
  // transverse shear α κ_s G t), read per pair in the force loop.
  m_hourglass.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double ti = m_thickness[i], alpha = m_params.hourglassCoefficient;
    m_hourglass[i] = {alpha * m.youngModulus * ti, alpha * m.youngModulus * ti * ti * ti / (12.0 * (1.0 - nu * nu)),
                      alpha * (shearModulus * ti)};
  }
  computePairHourglass();

  // Time step: the central-difference limit 2/ω_max with ω_max from the stiffest translation
  // (membrane P-wave, wave number k = 2.5/Δ, which bounds the corrected-kernel gradient operator
  // with its hourglass term; × √(t_j / t_i) at a step), the stiffest rotation (transverse shear
  // κGt and bending D k² against the rotary inertia s_I ρ t³/12; the thinnest node's is the
  // fastest) and, at a step, the rotation of the nodes beside it (above).
  const double t = *std::min_element(m_thickness.begin(), m_thickness.end());
  const double omegaTranslation = std::sqrt(cp2) * k * (1.0 + m_params.hourglassCoefficient) * std::sqrt(stiffnessRatio);
  const double omegaRotation =
      std::sqrt((12.0 * shearModulus / (rho * t * t) + cp2 * k * k) / m_params.rotaryInertiaScale);
  const double omegaStepRotation = std::sqrt(stepRotation2);
  m_stableStep = m_params.courantFactor * 2.0 / std::max({omegaTranslation, omegaRotation, omegaStepRotation});
  computeOwnSteps();
  m_boundPointStep = m_pointStep;
  m_boundStableStep = m_stableStep;
  m_pointStrain.assign(n, {});
  m_newlyFractured.assign(n, 0);
  m_classes.assignSingleRate(n);
  if (m_params.stepEstimate == ShellParameters::StepEstimate::Spectral) measureOwnSteps();
}

void SphShell::computePairHourglass() {
  // A pair's hourglass stiffnesses are its thinner node's (symmetric, and a thin plate next to a
  // thick step is not stiffened by its neighbour), times the pair's kernel weight hw.
  const std::size_t n = m_reference.size();
  m_pairHourglass.resize(m_neighbour.size());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {
      const std::size_t j = m_neighbour[p];
      const auto& X = m_separation[p];
      const double hw = m_kernel[p] * m_volume[i] * m_volume[j] / (X[0] * X[0] + X[1] * X[1]);
      const auto& k = m_hourglass[m_thickness[j] < m_thickness[i] ? j : i];
      m_pairHourglass[p] = {k[0] * hw, k[1] * hw, k[2] * hw};
    }
}

void SphShell::computeOwnSteps() {
  // The constructor's estimate with one node's or one stress point's own data instead of the
  // extremes over the plate (which stay the single-rate step, never above any of these).
  //  - A term of stress point j acting on node i: the pair's finer spacing (k = 2.5/Δ), j's
  //    thickness against i's mass (the translation's √(t_j / t_i), at least 1) and j's bending
  //    and shear stiffness against i's rotary inertia (ρ/12 × max(t_i³, f t_i t_thickest²)).
  //  - A node: the finest of the terms that reach it (its kernel's spacing, the thickest point).
  // A clamped node does not move and constrains nothing.
  const std::size_t n = m_reference.size();
  const ElasticPlasticMaterial& m = m_params.material;
  const double rho = m_params.density, nu = m.poissonRatio;
  const double cp2 = m.youngModulus / (rho * (1.0 - nu * nu));
  const double shearModulus = m_params.shearCorrection * m.shearModulus();
  const double sI = m_params.rotaryInertiaScale, hourglass = 1.0 + m_params.hourglassCoefficient;
  std::vector<double> inertia(n);  // × ρ/12 per unit area, as the constructor set m_inertia
  for (std::size_t i = 0; i < n; ++i) {
    double thickest = m_thickness[i];
    for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) thickest = std::max(thickest, m_thickness[m_neighbour[p]]);
    const double ti = m_thickness[i];
    inertia[i] = std::max(ti * ti * ti, thickest > ti ? m_params.stepRotaryInertia * ti * thickest * thickest : 0.0);
  }
  auto termStep = [&](std::size_t j, std::size_t i) {
    const double k = 2.5 / std::min(m_nodeSpacing[i], m_nodeSpacing[j]);
    const double tj = m_thickness[j], ti = m_thickness[i];
    const double translation2 = cp2 * k * k * hourglass * hourglass * std::max(1.0, tj / ti);
    const double rotation2 = (12.0 * shearModulus * tj / rho + cp2 * k * k * tj * tj * tj) / (sI * inertia[i]);
    return m_params.courantFactor * 2.0 / std::sqrt(std::max(translation2, rotation2));
  };
  const double never = std::numeric_limits<double>::infinity();
  m_ownStep.assign(n, never);
  m_pointStep.assign(n, never);
  for (std::size_t j = 0; j < n; ++j) {
    auto reach = [&](std::size_t i) {
      if (m_clamped[i]) return;
      const double h = std::max(termStep(j, i), m_stableStep);
      m_pointStep[j] = std::min(m_pointStep[j], h);
      m_ownStep[i] = std::min(m_ownStep[i], h);
    };
    reach(j);
    for (std::size_t p = m_offset[j]; p < m_offset[j + 1]; ++p) reach(m_neighbour[p]);
  }
}

void SphShell::buildNeighbours() {
  const std::size_t n = m_reference.size();
  const double radius = 2.0 * m_params.smoothingRatio * m_spacing;  // the longest link (Δ_i = Δ_j = Δ)
  // Bucket grid on the reference plane (built once: total Lagrangian).
  double xmin = m_reference[0][0], ymin = m_reference[0][1], xmax = xmin, ymax = ymin;
  for (const auto& p : m_reference) {
    xmin = std::min(xmin, p[0]); xmax = std::max(xmax, p[0]);
    ymin = std::min(ymin, p[1]); ymax = std::max(ymax, p[1]);
  }
  const long nx = static_cast<long>((xmax - xmin) / radius) + 1, ny = static_cast<long>((ymax - ymin) / radius) + 1;
  std::vector<std::vector<std::size_t>> cells(static_cast<std::size_t>(nx * ny));
  auto cellOf = [&](const std::array<double, 2>& p) {
    return std::array<long, 2>{std::min(nx - 1, static_cast<long>((p[0] - xmin) / radius)),
                               std::min(ny - 1, static_cast<long>((p[1] - ymin) / radius))};
  };
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = cellOf(m_reference[i]);
    cells[static_cast<std::size_t>(c[1] * nx + c[0])].push_back(i);
  }
  m_offset.assign(n + 1, 0);
  m_neighbour.clear();
  std::vector<std::size_t> found;
  for (std::size_t i = 0; i < n; ++i) {
    found.clear();
    const auto c = cellOf(m_reference[i]);
    for (long cy = std::max(0L, c[1] - 1); cy <= std::min(ny - 1, c[1] + 1); ++cy)
      for (long cx = std::max(0L, c[0] - 1); cx <= std::min(nx - 1, c[0] + 1); ++cx)
        for (std::size_t j : cells[static_cast<std::size_t>(cy * nx + cx)]) {
          if (j == i) continue;
          const double dx = m_reference[j][0] - m_reference[i][0], dy = m_reference[j][1] - m_reference[i][1];
          const double support = 2.0 * pairSmoothingLength(i, j);
          if (dx * dx + dy * dy < support * support) found.push_back(j);
        }
    std::sort(found.begin(), found.end());
    m_neighbour.insert(m_neighbour.end(), found.begin(), found.end());
    m_offset[i + 1] = m_neighbour.size();
    m_maxPairs = std::max(m_maxPairs, found.size());
  }
  const std::size_t pairs = m_neighbour.size();
  m_reverse.resize(pairs);
  m_separation.resize(pairs);
  m_kernel.resize(pairs);
  m_active.assign(pairs, 1);
  m_coeff.assign(pairs, {0.0, 0.0});
  m_coeffBack.assign(pairs, {0.0, 0.0});
  m_shearCoeff.assign(pairs, {0.0, 0.0});
  m_shearBack.assign(pairs, {0.0, 0.0});
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {
      const std::size_t j = m_neighbour[p];
      const WendlandC2Kernel2D kernel{pairSmoothingLength(i, j)};
      const auto first = m_neighbour.begin() + static_cast<long>(m_offset[j]);
      const auto last = m_neighbour.begin() + static_cast<long>(m_offset[j + 1]);
      m_reverse[p] = static_cast<std::size_t>(std::lower_bound(first, last, i) - m_neighbour.begin());
      m_separation[p] = {m_reference[j][0] - m_reference[i][0], m_reference[j][1] - m_reference[i][1]};
      m_kernel[p] = kernel.value(std::hypot(m_separation[p][0], m_separation[p][1]));
    }
}

void SphShell::correctNode(std::size_t i) {
  // M_i = Σ_j V_j (X_j − X_i) ⊗ ∇W(X_i − X_j); B_ij = M_i⁻ᵀ ∇W(X_i − X_j).
  double M[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
  int count = 0;
  for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {
    if (!m_active[p]) continue;
    const auto& d = m_separation[p];
    const double r = std::hypot(d[0], d[1]);
    const WendlandC2Kernel2D kernel{pairSmoothingLength(i, m_neighbour[p])};
    const double w = kernel.derivative(r) / r;  // ∇W(X_i − X_j) = W'(r) (−d)/r
    const double g0 = -w * d[0], g1 = -w * d[1];
    const double v = m_volume[m_neighbour[p]];
    M[0][0] += v * d[0] * g0; M[0][1] += v * d[0] * g1;
    M[1][0] += v * d[1] * g0; M[1][1] += v * d[1] * g1;
    ++count;
  }
  // T_i = Σ_j V_j W_ij X_ij ⊗ X_ij for the pair-averaged transverse shear.
  double T[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
  for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {
    if (!m_active[p]) continue;
    const auto& d = m_separation[p];
    const double vw = m_volume[m_neighbour[p]] * m_kernel[p];
    T[0][0] += vw * d[0] * d[0]; T[0][1] += vw * d[0] * d[1]; T[1][1] += vw * d[1] * d[1];
  }
  T[1][0] = T[0][1];
  const double detT = T[0][0] * T[1][1] - T[0][1] * T[1][0];
  const double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
  const double trace = M[0][0] + M[1][1];
  // A one-sided or collinear neighbourhood (a fragment, a node cut off by a crack) has no
  // first-order gradient.
  const double traceT = T[0][0] + T[1][1];
  const bool valid = count >= 3 && trace > 0.0 && det > 1e-3 * 0.25 * trace * trace &&
                     detT > 1e-3 * 0.25 * traceT * traceT;
  m_hasGradient[i] = valid ? 1 : 0;
  if (!valid) return;
  // M⁻ᵀ: inverse of the transpose.
  const double inv[2][2] = {{M[1][1] / det, -M[1][0] / det}, {-M[0][1] / det, M[0][0] / det}};
  for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {
    if (!m_active[p]) { m_coeff[p] = {0.0, 0.0}; m_shearCoeff[p] = {0.0, 0.0}; continue; }
    const auto& d = m_separation[p];
    const double r = std::hypot(d[0], d[1]);
    const WendlandC2Kernel2D kernel{pairSmoothingLength(i, m_neighbour[p])};
    const double w = kernel.derivative(r) / r;
    const double g0 = -w * d[0], g1 = -w * d[1];
    const double v = m_volume[m_neighbour[p]];
    m_coeff[p] = {v * (inv[0][0] * g0 + inv[0][1] * g1), v * (inv[1][0] * g0 + inv[1][1] * g1)};
    const double vw = v * m_kernel[p];
    m_shearCoeff[p] = {vw * (T[1][1] * d[0] - T[0][1] * d[1]) / detT, vw * (T[0][0] * d[1] - T[1][0] * d[0]) / detT};
  }
}

void SphShell::linkBackCoefficients(std::size_t i) {
  for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {
    const std::size_t j = m_neighbour[p];
    m_coeffBack[p] = (m_active[p] && m_hasGradient[j]) ? m_coeff[m_reverse[p]] : std::array<double, 2>{0.0, 0.0};
    m_shearBack[p] = (m_active[p] && m_hasGradient[j]) ? m_shearCoeff[m_reverse[p]] : std::array<double, 2>{0.0, 0.0};
    if (!m_hasGradient[i]) m_coeff[p] = m_shearCoeff[p] = {0.0, 0.0};
  }
}

void SphShell::buildCorrections() {
  const std::size_t n = m_reference.size();
  for (std::size_t i = 0; i < n; ++i) correctNode(i);
  for (std::size_t i = 0; i < n; ++i) linkBackCoefficients(i);
}

void SphShell::buildCorrections(const std::vector<std::size_t>& nodes) {
  // A node's corrections depend only on its own active links, so after a cut only the cut links'
  // ends change: the same values as the rebuild of every node, without its cost per fracture.
  for (std::size_t i : nodes) correctNode(i);
  for (std::size_t i : nodes) {
    linkBackCoefficients(i);
    for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {  // the neighbours' view of i
      const std::size_t r = m_reverse[p];
      const bool seen = m_active[r] && m_hasGradient[i];
      m_coeffBack[r] = seen ? m_coeff[p] : std::array<double, 2>{0.0, 0.0};
      m_shearBack[r] = seen ? m_shearCoeff[p] : std::array<double, 2>{0.0, 0.0};
    }
  }
}

void SphShell::currentGradients(std::size_t i, std::array<double, 6>& A, std::array<double, 6>& G) const {
  A = {}, G = {};
  if (!m_hasGradient[i]) {
    A = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0};
    return;
  }
  const ShellVec3 xi = m_position[i], ni = m_normal[i];
  for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {
    if (!m_active[p]) continue;
    const std::size_t j = m_neighbour[p];
    const auto& c = m_coeff[p];
    for (int a = 0; a < 3; ++a) {
      const double dx = m_position[j][a] - xi[a], dn = m_normal[j][a] - ni[a];
      A[a] += dx * c[0]; A[3 + a] += dx * c[1];
      G[a] += dn * c[0]; G[3 + a] += dn * c[1];
    }
  }
}

void SphShell::computeForces(double dt, int firing) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const std::size_t n = m_position.size();
  const std::size_t layers = m_rule.xi.size();
  const ElasticPlasticMaterial& mat = m_params.material;
  const double shearModulus = m_params.shearCorrection * mat.shearModulus();  // κ_s G
  // maxFrequency's probe: the elastic layers (its stiffness bounds a yielding one's), no damage.
  const bool plastic = m_params.plasticity && !m_elasticProbe, damaging = m_params.damage && plastic;
  const bool shearYield = plastic && m_params.transverseShearYield;
  const std::uint32_t* pointOrder = m_classes.pointOrder.data();
  const std::size_t points = m_classes.pointsUpTo[static_cast<std::size_t>(firing)];
  m_pointEvaluations += points;

  // Pass 1a: gradients and strains at the points that fire.
  const double* position = m_position.data()->data();
  const double* normal = m_normal.data()->data();
#pragma omp parallel
  {
  PairDirectors directors(m_maxPairs);
#pragma omp for schedule(static)
  for (std::size_t q = 0; q < points; ++q) {
    const std::size_t i = pointOrder[q];
    std::array<double, 6> A, G;
    currentGradients(i, A, G);
    m_gradX[i] = A;
    m_gradN[i] = G;
    if (m_hasGradient[i] && m_area[i] > 0.0 && !m_fractured[i]) {
      const ShellVec3 a0 = column(A, 0), a1 = column(A, 1), g0 = column(G, 0), g1 = column(G, 1);
      // Pair-averaged transverse shear γ_i = T_i⁻¹ Σ_j V_j W_ij s_ij X_ij, s_ij = (x_j − x_i)·n̄_ij:
      // exact for a uniform shear, and zero for any quadratic deflection with matching directors
      // (trapezoidal rule), so it does not lock where the node gradient of w is one-sided.
      double gam0 = 0.0, gam1 = 0.0;
      const std::size_t first = m_offset[i];
      pairShears(position, normal, m_neighbour.data(), i, first, m_offset[i + 1] - first, directors);
      for (std::size_t p = first; p < m_offset[i + 1]; ++p) {
        if (!m_active[p]) continue;
        const double sp = directors.shear()[p - first];
        gam0 += sp * m_shearCoeff[p][0];
        gam1 += sp * m_shearCoeff[p][1];
      }
      m_pointStrain[i] = {0.5 * (dot(a0, a0) - 1.0), 0.5 * (dot(a1, a1) - 1.0), 0.5 * dot(a0, a1),
                          dot(a0, g0),               dot(a1, g1),               0.5 * (dot(a0, g1) + dot(a1, g0)),
                          gam0,                      gam1};
    }
  }
  }
  const auto gradientsDone = Clock::now();

  // Pass 1b: the layers through the thickness and the resultants, each point's weighted by its
  // class's 2^c (exact: a power of two); the points that do not fire give no force this step.
  // Dealt out in small chunks as the threads free up: a layer that flows (a return mapping, the
  // damage) costs many times an elastic one, and the flowing points sit together (the band, the
  // rim), so halves of the list would leave one thread with most of them. Each point writes only
  // its own state: the same results for any schedule.
#pragma omp parallel for schedule(dynamic, 32)
  for (std::size_t q = 0; q < points; ++q) {
    const std::size_t i = pointOrder[q];
    std::array<double, 6> P{}, R{};
    std::array<double, 2> Qout{0.0, 0.0};
    PlaneTensor Mout{0.0, 0.0, 0.0};
    const bool stressPoint = m_hasGradient[i] && m_area[i] > 0.0 && !m_fractured[i];
    if (stressPoint) {
      const double weight = classWeight(m_classes.point[i]);
      const double pointDt = dt * weight;  // the interval this evaluation stands for
      const auto& A = m_gradX[i];
      const auto& G = m_gradN[i];
      const ShellVec3 a0 = column(A, 0), a1 = column(A, 1), g0 = column(G, 0), g1 = column(G, 1);
      const auto& strain = m_pointStrain[i];
      const PlaneTensor eps = {strain[0], strain[1], strain[2]};
      const PlaneTensor kap = {strain[3], strain[4], strain[5]};
      const double gam0 = strain[6], gam1 = strain[7];
      PlaneTensor N{0.0, 0.0, 0.0}, M{0.0, 0.0, 0.0};
      const double t = m_thickness[i], scale = t / m_params.thickness;
      double intact = 0.0;
      TransverseShear Q{0.0, 0.0};  // Σ w_k (1 − D_k) σ_k3 when the layers yield in shear
      int broken = 0;
      for (std::size_t k = 0; k < layers; ++k) {
        const double z = scale * m_rule.xi[k], w = scale * m_rule.weight[k];
        const PlaneTensor E = {eps[0] + z * kap[0], eps[1] + z * kap[1], eps[2] + z * kap[2]};
        const std::size_t idx = i * layers + k;
        PlaneTensor sig;
        TransverseShear tau{0.0, 0.0};
        if (plastic) {
          const double pBefore = m_plasticStrain[idx];
          ReturnMapping r;
          if (shearYield) {
            // The layer's share of the mean shear strain: parabolic, zero at the faces, with mean κ_s γ
            // (the resultant κ_s G t γ when elastic: Gauss integrates the parabola exactly).
            const double zeta = z / t, profile = 1.5 * (1.0 - 4.0 * zeta * zeta) * m_params.shearCorrection;
            const TransverseShear epsT = {0.5 * profile * gam0, 0.5 * profile * gam1};
            r = shellPointUpdate(mat, E, epsT, m_plasticStrainTensor[idx], m_plasticShear[idx], m_plasticStrain[idx],
                                 sig, tau);
          } else {
            r = planeStressPointUpdate(mat, E, m_plasticStrainTensor[idx], m_plasticStrain[idx], sig);
          }
          // A layer that neither flows nor has damage to catch up (the delay) leaves the damage as
          // it is: advanceDamage would change nothing, so the triaxiality is not worked out for it.
          const DamageState& before = m_damage[idx];
          const bool damageMoves = r.plasticStrainIncrement != 0.0 || before.undelayed > before.damage;
          if (damaging && damageMoves && !before.fractured) {  // tau is zero unless the layers yield in shear
            const double eta = triaxiality(hydrostaticStress(sig), vonMisesStress(sig, tau));
            advanceDamage(m_params.damageLaw, m_damage[idx], pBefore, r.plasticStrainIncrement, eta, pointDt);
          }
        } else {
          sig = planeStressElastic(mat, E);
        }
        const double f = stressFactor(m_damage[idx]);
        if (m_damage[idx].fractured) ++broken;
        intact += w * f;
        Q[0] += w * f * tau[0];
        Q[1] += w * f * tau[1];
        for (int c = 0; c < 3; ++c) {
          N[c] += w * f * sig[c];
          M[c] += w * z * f * sig[c];
        }
      }
      if (broken >= m_layersToFracture && !m_elasticProbe) m_newlyFractured[i] = 1;
      Mout = M;
      const double om = m_area[i] * weight;
      // Elastic shear: κ_s G t γ times the layers' mean (1 − D), Σ w_k (1 − D_k) / t.
      const double shearStiffness = shearModulus * t;
      const double Q0 = om * (shearYield ? Q[0] : shearStiffness * gam0 * intact / t);
      const double Q1 = om * (shearYield ? Q[1] : shearStiffness * gam1 * intact / t);
      Qout = {Q0, Q1};
      // P_α = Σ_β (N_αβ A_β + M_αβ G_β);  R_α = Σ_β M_αβ A_β (× ω_i); Q = ω_i κ_s G t γ.
      for (int c = 0; c < 3; ++c) {
        P[c] = om * (N[0] * a0[c] + N[2] * a1[c] + M[0] * g0[c] + M[2] * g1[c]);
        P[3 + c] = om * (N[2] * a0[c] + N[1] * a1[c] + M[2] * g0[c] + M[1] * g1[c]);
        R[c] = om * (M[0] * a0[c] + M[2] * a1[c]);
        R[3 + c] = om * (M[2] * a0[c] + M[1] * a1[c]);
      }
    }
    m_stressP[i] = P;
    m_stressR[i] = R;
    m_moment[i] = stressPoint ? std::array<double, 3>{Mout[0], Mout[1], Mout[2]} : std::array<double, 3>{0.0, 0.0, 0.0};
    m_shearQ[i] = Qout;
  }
#pragma omp parallel for schedule(static)
  for (std::size_t q = points; q < n; ++q) {
    const std::size_t i = pointOrder[q];
    m_stressP[i] = {};
    m_stressR[i] = {};
    m_shearQ[i] = {0.0, 0.0};
  }
  const auto layersDone = Clock::now();

  // Pass 2: gather the forces on the free nodes (no scatter, no atomics); a node that no firing
  // term reaches keeps only its external force.
  const double pressure = m_pressure;
  const std::uint32_t* gatherOrder = m_classes.gatherOrder.data();
  const std::uint8_t* nodeClass = m_classes.node.data();
  const std::size_t gathered = m_classes.gatherUpTo[static_cast<std::size_t>(firing)];
  // The nodes a term reaches are the first of gatherOrder: shared out on their own, so that both
  // threads gather at a step where only the finest class fires.
#pragma omp parallel for schedule(static)
  for (std::size_t q = gathered; q < n; ++q) {
    const std::size_t i = gatherOrder[q];
    ShellVec3 f{0.0, 0.0, 0.0};
    if (!m_clamped[i])
      for (int a = 0; a < 3; ++a) f[a] += m_external[i][a];
    m_force[i] = f;
    m_directorForce[i] = {0.0, 0.0, 0.0};
  }
#pragma omp parallel
  {
  PairDirectors directors(m_maxPairs);
#pragma omp for schedule(static)
  for (std::size_t q = 0; q < gathered; ++q) {
    const std::size_t i = gatherOrder[q];
    ShellVec3 f{0.0, 0.0, 0.0}, g{0.0, 0.0, 0.0};
    if (m_clamped[i]) { m_force[i] = f; m_directorForce[i] = g; continue; }
    const std::size_t first = m_offset[i];
    pairMeanDirectors(normal, m_neighbour.data(), i, first, m_offset[i + 1] - first, directors);
    const auto& Pi = m_stressP[i];
    const auto& Ri = m_stressR[i];
    const auto& Ai = m_gradX[i];
    const auto& Gi = m_gradN[i];
    const bool ownPointFires = m_classes.point[i] <= firing;
    for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {
      if (!m_active[p]) continue;
      const std::size_t j = m_neighbour[p];
      // A pair none of whose terms fires (point i's, point j's, the hourglass) adds nothing.
      const int pairClass = std::min(nodeClass[i], nodeClass[j]);
      if (!ownPointFires && m_classes.point[j] > firing && pairClass > firing) continue;
      const auto& c = m_coeff[p];
      const auto& b = m_coeffBack[p];
      const auto& Pj = m_stressP[j];
      const auto& Rj = m_stressR[j];
      const auto& Aj = m_gradX[j];
      const auto& Gj = m_gradN[j];
      const auto& X = m_separation[p];
      // The hourglass stiffnesses (times hw) of a pair that fires, times its class's 2^c; a pair
      // that does not fire this step gives only the points' forces.
      const double pairWeight = pairClass <= firing ? classWeight(pairClass) : 0.0;
      const auto& stiffness = m_pairHourglass[p];
      const double kx = stiffness[0] * pairWeight, kn = stiffness[1] * pairWeight, ks = stiffness[2] * pairWeight;
      // Hourglass control. Tangential: error of the separation predicted by the mean gradient
      // (exact for quadratic fields). Normal: the separation along the mean director, a pair
      // transverse-shear measure that vanishes for Kirchhoff–Mindlin bending to third order even
      // where the field is only C¹ (at a clamp), unlike a gradient prediction of w.
      ShellVec3 dx, ex;
      for (int a = 0; a < 3; ++a) {
        dx[a] = m_position[j][a] - m_position[i][a];
        ex[a] = 0.5 * ((Ai[a] + Aj[a]) * X[0] + (Ai[3 + a] + Aj[3 + a]) * X[1]) - dx[a];
      }
      const double meanLength = directors.length()[p - first];
      const ShellVec3 mean = {directors.mean(0)[p - first], directors.mean(1)[p - first], directors.mean(2)[p - first]};
      const double exNormal = dot(ex, mean), dxNormal = dot(dx, mean);
      // Transverse shear: E = Σ_i ½ Q_i·γ_i with γ_i linear in s_ij = Δx·n̄.
      const double q = m_shearQ[i][0] * m_shearCoeff[p][0] + m_shearQ[i][1] * m_shearCoeff[p][1] -
                       m_shearQ[j][0] * m_shearBack[p][0] - m_shearQ[j][1] * m_shearBack[p][1];
      for (int a = 0; a < 3; ++a) {
        f[a] += Pi[a] * c[0] + Pi[3 + a] * c[1] - Pj[a] * b[0] - Pj[3 + a] * b[1];
        g[a] += Ri[a] * c[0] + Ri[3 + a] * c[1] - Rj[a] * b[0] - Rj[3 + a] * b[1];
        const double en = 0.5 * ((Gi[a] + Gj[a]) * X[0] + (Gi[3 + a] + Gj[3 + a]) * X[1]) -
                          (m_normal[j][a] - m_normal[i][a]);
        f[a] -= kx * (ex[a] - exNormal * mean[a]);
        // E = ½ k_s hw (Δx·n̄)², n̄ = (n_i + n_j)/|n_i + n_j|: −∂E/∂x_i and −∂E/∂n_i.
        f[a] += (ks * dxNormal + q) * mean[a];
        g[a] -= (ks * dxNormal + q) * (dx[a] - dxNormal * mean[a]) / meanLength;
        g[a] -= kn * en;
      }
    }
    if (pressure != 0.0 && !m_fractured[i] && m_classes.point[i] <= firing) {
      const ShellVec3 areaNormal = m_hasGradient[i] ? cross(column(Ai, 0), column(Ai, 1)) : m_normal[i];
      const double load = pressure * classWeight(m_classes.point[i]);
      for (int a = 0; a < 3; ++a) f[a] += load * m_area[i] * areaNormal[a];
    }
    for (int a = 0; a < 3; ++a) f[a] += m_external[i][a];
    m_force[i] = f;
    m_directorForce[i] = g;
  }
  }

  const auto forcesDone = Clock::now();
  m_timings.gradients += std::chrono::duration<double>(gradientsDone - start).count();
  m_timings.layers += std::chrono::duration<double>(layersDone - gradientsDone).count();
  m_timings.forces += std::chrono::duration<double>(forcesDone - layersDone).count();
}

void SphShell::step(double dt) {
  if (!m_classes.singleRate()) m_classes.assignSingleRate(m_position.size());
  fineStep(dt, 0);
}

long SphShell::advanceInterval(double dt) {
  const std::size_t n = m_position.size();
  // The spectral estimate is measured again once the cuts have rebuilt the gradients of enough
  // nodes: a node that lost links can have a larger corrected gradient, hence a faster mode.
  if (m_params.stepEstimate == ShellParameters::StepEstimate::Spectral &&
      m_rebuiltSinceMeasure >= std::max<std::size_t>(1, n / kSpectrumRemeasureFraction))
    measureOwnSteps();
  SubcyclingPlan plan;
  // The multi-rate scheme's own steps: under the measured estimate, at most kMultiRateCourantFactor
  // of each class's limit (shell/step_classes.hpp: the coarser classes' impulses); the bound's
  // are far enough below the limit as they are.
  const double multiRate = m_params.stepEstimate == ShellParameters::StepEstimate::Spectral
                               ? std::min(1.0, kMultiRateCourantFactor / m_params.courantFactor)
                               : 1.0;
  std::vector<double> multiRatePointStep, multiRateNodeStep;
  if (m_params.subcycling && multiRate < 1.0) {
    multiRatePointStep = m_pointStep, multiRateNodeStep = m_ownStep;
    for (double& h : multiRatePointStep) h *= multiRate;
    for (double& h : multiRateNodeStep) h *= multiRate;
  }
  const auto& pointStep = multiRate < 1.0 ? multiRatePointStep : m_pointStep;
  const auto& nodeStep = multiRate < 1.0 ? multiRateNodeStep : m_ownStep;
  if (m_params.subcycling) {
    plan = planSubcycling(pointStep, m_stableStep, dt, multiRate * m_stableStep);
  } else {
    plan.fineSteps = std::max(1L, static_cast<long>(std::ceil(dt / m_stableStep * (1.0 - 1e-12))));
    plan.fineStep = dt / static_cast<double>(plan.fineSteps);
  }
  if (plan.coarsest == 0) {
    if (!m_classes.singleRate()) m_classes.assignSingleRate(n);
  } else {
    m_classes.assign(nodeStep, pointStep, plan, m_offset, m_neighbour);
  }
  for (long k = 0; k < plan.fineSteps; ++k) fineStep(plan.fineStep, firingClass(k, plan.coarsest));
  return plan.fineSteps;
}

void SphShell::fineStep(double dt, int firing) {
  computeForces(dt, firing);
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = m_position.size();
  const double c = m_params.dampingRate;
  const double keep = (1.0 - 0.5 * c * dt) / (1.0 + 0.5 * c * dt), push = dt / (1.0 + 0.5 * c * dt);
  // Over the nodes in the gather's order and split as its two loops are, so that each thread
  // moves the nodes whose forces it has just written (in cache, not the other core's).
  const std::uint32_t* gatherOrder = m_classes.gatherOrder.data();
  const std::size_t gathered = m_classes.gatherUpTo[static_cast<std::size_t>(firing)];
  auto integrate = [&](std::size_t i) {
    if (m_clamped[i]) return;
    // Central difference (leapfrog) with mass-proportional damping, semi-implicit in c.
    for (int a = 0; a < 3; ++a) {
      m_velocity[i][a] = keep * m_velocity[i][a] + push * m_force[i][a] / m_mass[i];
      m_position[i][a] += dt * m_velocity[i][a];
    }
    // Director: torque n × g on the rotary inertia; no drilling (spin kept perpendicular to n).
    ShellVec3& n0 = m_normal[i];
    const ShellVec3 torque = cross(n0, m_directorForce[i]);
    ShellVec3& w = m_spin[i];
    for (int a = 0; a < 3; ++a) w[a] = keep * w[a] + push * torque[a] / m_inertia[i];
    const double along = dot(w, n0);
    for (int a = 0; a < 3; ++a) w[a] -= along * n0[a];
    const double angle = std::sqrt(dot(w, w)) * dt;
    if (angle > 0.0) {
      // Rodrigues rotation of n about w by |w| dt (w ⟂ n).
      const double wn = std::sqrt(dot(w, w));
      const ShellVec3 axis = {w[0] / wn, w[1] / wn, w[2] / wn};
      const ShellVec3 k = cross(axis, n0);
      const double cs = std::cos(angle), sn = std::sin(angle);
      ShellVec3 rotated;
      for (int a = 0; a < 3; ++a) rotated[a] = n0[a] * cs + k[a] * sn;
      const double len = std::sqrt(dot(rotated, rotated));
      for (int a = 0; a < 3; ++a) n0[a] = rotated[a] / len;
    }
  };
#pragma omp parallel for schedule(static)
  for (std::size_t q = gathered; q < n; ++q) integrate(gatherOrder[q]);
#pragma omp parallel for schedule(static)
  for (std::size_t q = 0; q < gathered; ++q) integrate(gatherOrder[q]);
  const auto integrated = std::chrono::steady_clock::now();
  // Fracture after the motion, as before the passes were split (the same state either way: the
  // fracture cuts links, it does not move nodes).
  for (std::size_t i = 0; i < n; ++i)
    if (m_newlyFractured[i]) {
      m_newlyFractured[i] = 0;
      if (!m_fractured[i]) fractureNode(i);
    }
  m_time += dt;
  m_timings.integration += std::chrono::duration<double>(integrated - start).count();
  m_timings.fracture += std::chrono::duration<double>(std::chrono::steady_clock::now() - integrated).count();
}

void SphShell::setNodeState(std::size_t i, const ShellVec3& position, const ShellVec3& normal,
                            const ShellVec3& velocity) {
  const double len = std::sqrt(dot(normal, normal));
  if (i >= m_position.size() || !(len > 0.0)) throw std::invalid_argument("SphShell::setNodeState: bad node or normal");
  m_position[i] = position;
  m_normal[i] = {normal[0] / len, normal[1] / len, normal[2] / len};
  m_velocity[i] = velocity;
}

void SphShell::advance(int steps, double dt, const Cancellation& cancel) {
  for (int s = 0; s < steps; ++s) {
    cancel.throwIfRequested();
    step(dt);
  }
}

double SphShell::maxPlasticStrain(std::size_t i) const {
  const std::size_t layers = m_rule.xi.size();
  double v = 0.0;
  for (std::size_t k = 0; k < layers; ++k) v = std::max(v, m_plasticStrain[i * layers + k]);
  return v;
}

int SphShell::failedLayers(std::size_t i) const {
  const std::size_t layers = m_rule.xi.size();
  int count = 0;
  for (std::size_t k = 0; k < layers; ++k) count += m_damage[i * layers + k].fractured ? 1 : 0;
  return count;
}

double SphShell::maxDamage(std::size_t i) const {
  const std::size_t layers = m_rule.xi.size();
  double v = 0.0;
  for (std::size_t k = 0; k < layers; ++k) v = std::max(v, m_damage[i * layers + k].damage);
  return v;
}

std::size_t SphShell::fracturedCount() const {
  return static_cast<std::size_t>(std::count(m_fractured.begin(), m_fractured.end(), std::uint8_t{1}));
}

double SphShell::kineticEnergy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < m_position.size(); ++i)
    e += 0.5 * m_mass[i] * dot(m_velocity[i], m_velocity[i]) + 0.5 * m_inertia[i] * dot(m_spin[i], m_spin[i]);
  return e;
}

double SphShell::strainEnergy() const {
  const std::size_t n = m_position.size();
  const std::size_t layers = m_rule.xi.size();
  const ElasticPlasticMaterial& mat = m_params.material;
  const double G = mat.shearModulus(), shearModulus = m_params.shearCorrection * G;
  const bool shearYield = m_params.plasticity && m_params.transverseShearYield;
  // The gradients at the current positions (a subcycled point's stored ones may be older).
  std::vector<std::array<double, 6>> gradX(n), gradN(n);
  for (std::size_t i = 0; i < n; ++i) currentGradients(i, gradX[i], gradN[i]);
  double energy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(m_hasGradient[i] && m_area[i] > 0.0 && !m_fractured[i])) continue;
    const ShellVec3 a0 = column(gradX[i], 0), a1 = column(gradX[i], 1);
    const ShellVec3 g0 = column(gradN[i], 0), g1 = column(gradN[i], 1);
    const PlaneTensor eps = {0.5 * (dot(a0, a0) - 1.0), 0.5 * (dot(a1, a1) - 1.0), 0.5 * dot(a0, a1)};
    const PlaneTensor kap = {dot(a0, g0), dot(a1, g1), 0.5 * (dot(a0, g1) + dot(a1, g0))};
    double gam0 = 0.0, gam1 = 0.0;
    for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {
      if (!m_active[p]) continue;
      const double sp = pairShear(m_position[i], m_position[m_neighbour[p]], m_normal[i], m_normal[m_neighbour[p]]);
      gam0 += sp * m_shearCoeff[p][0], gam1 += sp * m_shearCoeff[p][1];
    }
    const double t = m_thickness[i], scale = t / m_params.thickness;
    double density = 0.0, intact = 0.0;  // per unit area
    for (std::size_t k = 0; k < layers; ++k) {
      const double z = scale * m_rule.xi[k], w = scale * m_rule.weight[k];
      const std::size_t idx = i * layers + k;
      const auto& Ep = m_plasticStrainTensor[idx];
      const PlaneTensor Ee = {eps[0] + z * kap[0] - Ep[0], eps[1] + z * kap[1] - Ep[1], eps[2] + z * kap[2] - Ep[2]};
      const PlaneTensor sig = planeStressElastic(mat, Ee);
      const double f = stressFactor(m_damage[idx]);
      intact += w * f;
      density += 0.5 * w * f * (sig[0] * Ee[0] + sig[1] * Ee[1] + 2.0 * sig[2] * Ee[2]);
      if (shearYield) {
        const double zeta = z / t, profile = 1.5 * (1.0 - 4.0 * zeta * zeta) * m_params.shearCorrection;
        const double e0 = 0.5 * profile * gam0 - m_plasticShear[idx][0], e1 = 0.5 * profile * gam1 - m_plasticShear[idx][1];
        density += 0.5 * w * f * 2.0 * G * 2.0 * (e0 * e0 + e1 * e1);
      }
    }
    if (!shearYield) density += 0.5 * shearModulus * intact * (gam0 * gam0 + gam1 * gam1);
    energy += m_area[i] * density;
  }
  // The hourglass springs, once per pair: ½ hw (k_x |e_x,t|² + k_n |e_n|² + k_s (Δx·n̄)²).
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {
      const std::size_t j = m_neighbour[p];
      if (j < i || !m_active[p]) continue;
      const auto& X = m_separation[p];
      const auto& [kx, kn, ks] = m_pairHourglass[p];  // × hw
      ShellVec3 dx, ex, en, mean;
      for (int a = 0; a < 3; ++a) {
        dx[a] = m_position[j][a] - m_position[i][a];
        ex[a] = 0.5 * ((gradX[i][a] + gradX[j][a]) * X[0] + (gradX[i][3 + a] + gradX[j][3 + a]) * X[1]) - dx[a];
        en[a] = 0.5 * ((gradN[i][a] + gradN[j][a]) * X[0] + (gradN[i][3 + a] + gradN[j][3 + a]) * X[1]) -
                (m_normal[j][a] - m_normal[i][a]);
        mean[a] = m_normal[i][a] + m_normal[j][a];
      }
      const double meanLength = std::sqrt(dot(mean, mean));
      for (int a = 0; a < 3; ++a) mean[a] /= meanLength;
      const double exNormal = dot(ex, mean), dxNormal = dot(dx, mean);
      energy += 0.5 * (kx * (dot(ex, ex) - exNormal * exNormal) + kn * dot(en, en) + ks * dxNormal * dxNormal);
    }
  return energy;
}

void SphShell::fractureNode(std::size_t i) {
  const std::size_t layers = m_rule.xi.size();
  for (std::size_t k = 0; k < layers; ++k) {
    DamageState& s = m_damage[i * layers + k];
    s.damage = std::max(s.damage, m_params.damageLaw.criticalDamage);
    s.fractured = true;
  }
  if (!m_fractured[i]) {
    m_fractureTime[i] = m_time;
    m_fractureOrder.push_back(i);
  }
  m_fractured[i] = 1;
  rebuildAfterCuts(cutLinksOf(i));
}

void SphShell::rebuildAfterCuts() {
  // Nodes left without a first-order gradient become fragments: their links go too.
  for (bool changed = true; changed;) {
    buildCorrections();
    m_rebuiltSinceMeasure += m_position.size();
    changed = !cutFragmentLinks().empty();
  }
}

void SphShell::rebuildAfterCuts(std::vector<std::size_t> touched) {
  // As rebuildAfterCuts(), rebuilding only the nodes whose links were cut (the others' corrections
  // would come out the same); the search for fragments still covers every node, as there.
  while (!touched.empty()) {
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    buildCorrections(touched);
    m_rebuiltSinceMeasure += touched.size();
    touched = cutFragmentLinks();
  }
}

std::vector<std::size_t> SphShell::cutFragmentLinks() {
  std::vector<std::size_t> ends;
  for (std::size_t j = 0; j < m_position.size(); ++j) {
    if (m_hasGradient[j]) continue;
    for (std::size_t p = m_offset[j]; p < m_offset[j + 1]; ++p)
      if (m_active[p]) {
        m_active[p] = 0;
        m_active[m_reverse[p]] = 0;
        ends.push_back(j);
        ends.push_back(m_neighbour[p]);
      }
  }
  return ends;
}

namespace {
/// True when the segments [p, q] and [a, b] cross at a point interior to both.
bool segmentsCross(const std::array<double, 2>& p, const std::array<double, 2>& q, const std::array<double, 2>& a,
                   const std::array<double, 2>& b) {
  auto orient = [](const std::array<double, 2>& o, const std::array<double, 2>& u, const std::array<double, 2>& v) {
    return (u[0] - o[0]) * (v[1] - o[1]) - (u[1] - o[1]) * (v[0] - o[0]);
  };
  return orient(p, q, a) * orient(p, q, b) < 0.0 && orient(a, b, p) * orient(a, b, q) < 0.0;
}
}  // namespace

void SphShell::cutAlongSegment(const std::array<double, 2>& a, const std::array<double, 2>& b) {
  cutAlongSegments({{a, b}});
}

void SphShell::cutAlongSegments(const std::vector<std::array<std::array<double, 2>, 2>>& segments) {
  const double reach = 2.0 * m_params.smoothingRatio * m_spacing;  // the longest link
  for (const auto& [a, b] : segments) {
    // Only nodes within a link's length of the segment's bounding box can own a crossing link.
    const double xmin = std::min(a[0], b[0]) - reach, xmax = std::max(a[0], b[0]) + reach;
    const double ymin = std::min(a[1], b[1]) - reach, ymax = std::max(a[1], b[1]) + reach;
    for (std::size_t i = 0; i < m_reference.size(); ++i) {
      const auto& X = m_reference[i];
      if (X[0] < xmin || X[0] > xmax || X[1] < ymin || X[1] > ymax) continue;
      for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p)
        if (m_active[p] && segmentsCross(X, m_reference[m_neighbour[p]], a, b)) {
          m_active[p] = 0;
          m_active[m_reverse[p]] = 0;
        }
    }
  }
  rebuildAfterCuts();
}

std::size_t SphShell::linksCrossing(const std::array<double, 2>& a, const std::array<double, 2>& b) const {
  std::size_t count = 0;
  for (std::size_t i = 0; i < m_reference.size(); ++i)
    for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p)
      if (m_active[p] && m_neighbour[p] > i && segmentsCross(m_reference[i], m_reference[m_neighbour[p]], a, b))
        ++count;
  return count;
}

std::vector<std::size_t> SphShell::cutLinksOf(std::size_t i) {
  // The cracked cell is an opaque disc of radius √V/2 (visibility criterion, Belytschko et al.
  // 1994): its own links go, and so does every link whose segment crosses the disc.
  const double rc = 0.5 * std::sqrt(m_volume[i]);
  std::vector<std::size_t> ends{i};
  for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {
    m_active[p] = 0;
    m_active[m_reverse[p]] = 0;
    ends.push_back(m_neighbour[p]);
  }
  for (std::size_t p = m_offset[i]; p < m_offset[i + 1]; ++p) {
    const std::size_t j = m_neighbour[p];
    for (std::size_t q = m_offset[j]; q < m_offset[j + 1]; ++q) {
      if (!m_active[q]) continue;
      const std::size_t k = m_neighbour[q];
      if (segmentDistance(m_reference[j], m_reference[k], m_reference[i]) < rc) {
        m_active[q] = 0;
        m_active[m_reverse[q]] = 0;
        ends.push_back(k);  // j is among i's neighbours already
      }
    }
  }
  return ends;
}

void SphShell::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "shell");
  archive.expectCount("nodes", size());
  archive.value("pressure", m_pressure), archive.value("time", m_time), archive.value("stable_step", m_stableStep);
  archive.records("reference", m_reference);
  archive.array("volume", m_volume), archive.array("area", m_area), archive.array("mass", m_mass);
  archive.array("inertia", m_inertia);
  archive.array("clamped", m_clamped), archive.array("fractured", m_fractured);
  archive.array("has_gradient", m_hasGradient);
  archive.array("fracture_time", m_fractureTime), archive.array("fracture_order", m_fractureOrder);
  archive.records("position", m_position), archive.records("velocity", m_velocity);
  archive.records("normal", m_normal), archive.records("spin", m_spin), archive.records("force", m_force);
  archive.records("director_force", m_directorForce), archive.records("external", m_external);
  archive.records("grad_x", m_gradX), archive.records("grad_n", m_gradN);
  archive.records("stress_p", m_stressP), archive.records("stress_r", m_stressR);
  archive.records("shear_q", m_shearQ);
  archive.records("plastic_strain_tensor", m_plasticStrainTensor);
  archive.array("plastic_strain", m_plasticStrain);
  archive.records("plastic_shear", m_plasticShear);
  archive.records("damage", m_damage);
  archive.array("offset", m_offset), archive.array("neighbour", m_neighbour), archive.array("reverse", m_reverse);
  archive.array("active", m_active);
  archive.records("separation", m_separation), archive.records("coeff", m_coeff);
  archive.records("coeff_back", m_coeffBack), archive.records("shear_coeff", m_shearCoeff);
  archive.records("shear_back", m_shearBack);
  archive.array("kernel", m_kernel);
  archive.value("point_evaluations", m_pointEvaluations);
  archive.record("timings", m_timings);
  archive.array("point_step", m_pointStep), archive.array("node_step", m_ownStep);
  archive.array("group_frequency", m_groupFrequency);
  archive.value("rebuilt_since_measure", m_rebuiltSinceMeasure);
  archive.value("spectrum_measurements", m_spectrumMeasurements);
  computePairHourglass();  // derived from the arrays just read (or written)
  m_maxPairs = 0;
  for (std::size_t i = 0; i + 1 < m_offset.size(); ++i) m_maxPairs = std::max(m_maxPairs, m_offset[i + 1] - m_offset[i]);
}

}  // namespace rupture
