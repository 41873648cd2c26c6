#include "calibration/elastic_relaxation.hpp"

#include <algorithm>
#include <cmath>

namespace rupture {

namespace {

constexpr double kInitialPoissonGuess = 0.25;

// Least-squares slope of u(c) over all elements.
double slope(const std::vector<double>& c, const std::vector<double>& u) {
  double mc = 0, mu = 0;
  for (std::size_t k = 0; k < c.size(); ++k) { mc += c[k]; mu += u[k]; }
  mc /= static_cast<double>(c.size());
  mu /= static_cast<double>(c.size());
  double num = 0, den = 0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    num += (c[k] - mc) * (u[k] - mu);
    den += (c[k] - mc) * (c[k] - mc);
  }
  return den > 0 ? num / den : 0.0;
}

}  // namespace

ElasticRelaxation::ElasticRelaxation(const BondedSystem& sample, const SampleSpec& spec,
                                     const CalibrationOptions& options)
    : m_options(options), m_system(sample) {
  BondedSystem& s = m_system;
  ParticleStore& p = s.particles;
  const std::size_t n = p.size();
  if (n < 4) throw CalibrationError("calibration needs a sample of at least 4 elements");
  s.beam.failureStress = 0;  // unbreakable: an elastic measurement
  ContactParameters noContact = s.contact.parameters();
  noContact.enabled = false;
  s.contact.setParameters(noContact);
  s.localDamping = options.damping;
  s.prescribe = nullptr;

  m_faces = tensionFaces(p);
  if (m_faces.xmin.empty() || m_faces.xmax.empty()) throw CalibrationError("calibration: sample has no X faces");
  m_x0 = p.x; m_y0 = p.y; m_z0 = p.z;
  double xc = 0, yc = 0, zc = 0;
  for (std::size_t k = 0; k < n; ++k) { xc += m_x0[k]; yc += m_y0[k]; zc += m_z0[k]; }
  xc /= static_cast<double>(n); yc /= static_cast<double>(n); zc /= static_cast<double>(n);

  const double eps = options.strain;
  for (std::size_t k = 0; k < n; ++k) {
    p.x[k] = m_x0[k] + eps * (m_x0[k] - xc);
    p.y[k] = m_y0[k] - kInitialPoissonGuess * eps * (m_y0[k] - yc);
    if (p.dimension == 3) p.z[k] = m_z0[k] - kInitialPoissonGuess * eps * (m_z0[k] - zc);
    p.vx[k] = p.vy[k] = p.vz[k] = 0;
    p.fixedDofs[k] = 0;
  }
  for (std::size_t k : m_faces.xmin) p.fixedDofs[k] = kFixX;
  for (std::size_t k : m_faces.xmax) p.fixedDofs[k] = kFixX;
  s.initialize();
  m_dt = options.timeStepSafety * s.criticalTimeStep();
  m_section = tensionSection(spec);
  // A check every few wave transits of the sample, counted in steps from the element count across.
  const double across = std::sqrt(static_cast<double>(n));
  m_interval = std::max<std::size_t>(200, static_cast<std::size_t>(4 * across));
  m_previous = measure();
}

ElasticProperties ElasticRelaxation::measure() const {
  const ParticleStore& p = m_system.particles;
  const std::size_t n = p.size();
  const double eps = m_options.strain;
  const double stress = meanFaceStress(p, m_faces, m_section);
  std::vector<double> uy(n), uz(n);
  for (std::size_t k = 0; k < n; ++k) { uy[k] = p.y[k] - m_y0[k]; uz[k] = p.z[k] - m_z0[k]; }
  double lateral = slope(m_y0, uy);
  if (p.dimension == 3) lateral = 0.5 * (lateral + slope(m_z0, uz));
  return ElasticProperties{stress / eps, -lateral / eps, m_system.steps, false};
}

ElasticProperties ElasticRelaxation::run() {
  BondedSystem& s = m_system;
  const CalibrationOptions& o = m_options;
  ElasticProperties current = m_previous;
  // Polled before every step, so a large sample stops within one step.
  while (s.steps < o.maxSteps) {
    for (; m_inInterval < m_interval; ++m_inInterval) {
      if (stopBeforeStep(o, s.steps)) {
        m_stopped = true;
        current.steps = s.steps;
        return current;
      }
      s.step(m_dt);
    }
    m_inInterval = 0;
    current = measure();
    const double dE = std::abs(current.youngModulus - m_previous.youngModulus) / std::abs(current.youngModulus);
    const double dNu = std::abs(current.poissonRatio - m_previous.poissonRatio);
    if (dE < o.tolerance && dNu < o.tolerance) {
      current.converged = true;
      break;
    }
    if (o.progress) {
      // The changes fall roughly geometrically: estimate the fraction done on a log scale
      // between the first change and the tolerance, bounded by the step budget.
      const double change = std::max({dE, dNu, o.tolerance});
      if (m_firstChange == 0) m_firstChange = std::max(change, o.tolerance * 1.0001);
      const double byChange = std::log(m_firstChange / change) / std::log(m_firstChange / o.tolerance);
      const double bySteps = static_cast<double>(s.steps) / static_cast<double>(o.maxSteps);
      o.progress(std::clamp(std::max(byChange, bySteps), 0.0, 1.0));
    }
    m_previous = current;
  }
  current.steps = s.steps;
  return current;
}

void ElasticRelaxation::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "elastic_relaxation");
  m_system.exchangeState(archive);
  archive.value("steps_in_interval", m_inInterval);
  archive.record("previous_check", m_previous);
  archive.value("first_change", m_firstChange);
}

}  // namespace rupture
