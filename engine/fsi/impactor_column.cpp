#include "fsi/impactor_column.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rupture::fsi {

std::string toString(ImpactorModel model) {
  switch (model) {
    case ImpactorModel::Rigid: return "rigid";
    case ImpactorModel::TwoBody: return "two_body";
    case ImpactorModel::ElasticPiston: return "elastic_piston";
  }
  return "rigid";
}

std::string toString(CarriageContact contact) {
  return contact == CarriageContact::Tied ? "tied" : "compression_only";
}

double ImpactorSpec::pistonArea() const { return 0.25 * std::numbers::pi * pistonDiameter * pistonDiameter; }
double ImpactorSpec::pistonMass() const { return pistonDensity * pistonArea() * pistonLength; }
double ImpactorSpec::resolvedContactStiffness() const {
  return contactStiffness > 0.0 ? contactStiffness : pistonYoungModulus * pistonArea() / 0.005;
}

ImpactorColumn::ImpactorColumn(const ImpactorSpec& spec, double gravity)
    : m_contactStiffness(spec.resolvedContactStiffness()),
      m_tied(spec.contact == CarriageContact::Tied),
      m_gravity(gravity) {
  if (spec.model == ImpactorModel::Rigid)
    throw std::logic_error("ImpactorColumn: the rigid impactor is the SPH piston body itself");
  const double pistonMass = spec.pistonMass();
  m_mass.push_back(spec.mass);
  if (spec.model == ImpactorModel::TwoBody) {
    m_mass.push_back(pistonMass);
  } else {
    const int n = spec.pistonElements;
    const double element = pistonMass / n;
    m_elementStiffness = spec.pistonYoungModulus * spec.pistonArea() / (spec.pistonLength / n);
    for (int k = 0; k <= n; ++k) m_mass.push_back(k == 0 || k == n ? 0.5 * element : element);
  }
  m_u.assign(m_mass.size(), 0.0);
  m_v.assign(m_mass.size(), 0.0);
  m_v[0] = spec.speed;
  m_f.assign(m_mass.size(), 0.0);
  // Gershgorin's bound on the largest eigenvalue of M⁻¹K: ω² ≤ max_i 2 Σ_j k_ij / m_i; the
  // leapfrog is stable for dt < 2/ω.
  double omega2 = 0.0;
  for (std::size_t i = 0; i < m_mass.size(); ++i) {
    double k = 0.0;
    if (i <= 1) k += m_contactStiffness;  // the carriage and the piston's struck face
    if (i >= 1 && i + 1 < m_mass.size()) k += m_elementStiffness;
    if (i >= 2) k += m_elementStiffness;
    omega2 = std::max(omega2, 2.0 * k / m_mass[i]);
  }
  m_stableStep = 0.9 * 2.0 / std::sqrt(omega2);
  computeForces(0.0);
}

void ImpactorColumn::computeForces(double faceForce) {
  for (std::size_t i = 0; i < m_mass.size(); ++i) m_f[i] = m_mass[i] * m_gravity;
  const double contact = contactForce();
  m_f[0] -= contact;
  m_f[1] += contact;
  for (std::size_t i = 1; i + 1 < m_mass.size(); ++i) {
    const double compression = m_elementStiffness * (m_u[i] - m_u[i + 1]);
    m_f[i] -= compression;
    m_f[i + 1] += compression;
  }
  m_f.back() += faceForce;
}

double ImpactorColumn::contactForce() const {
  const double closure = m_u[0] - m_u[1];
  return m_contactStiffness * (m_tied ? closure : std::max(0.0, closure));
}

void ImpactorColumn::advance(double dt, double faceForce) {
  const int n = std::max(1, static_cast<int>(std::ceil(dt / m_stableStep * (1.0 - 1e-12))));
  const double h = dt / n, faceStart = m_u.back();
  // The forces of the last sub-step were computed under the last step's face force: refresh them.
  computeForces(faceForce);
  for (int s = 0; s < n; ++s) {
    for (std::size_t i = 0; i < m_mass.size(); ++i) {
      m_v[i] += 0.5 * h * m_f[i] / m_mass[i];
      m_u[i] += h * m_v[i];
    }
    computeForces(faceForce);
    for (std::size_t i = 0; i < m_mass.size(); ++i) m_v[i] += 0.5 * h * m_f[i] / m_mass[i];
  }
  m_faceWork += faceForce * (m_u.back() - faceStart);
}

double ImpactorColumn::pistonMass() const {
  double m = 0.0;
  for (std::size_t i = 1; i < m_mass.size(); ++i) m += m_mass[i];
  return m;
}

double ImpactorColumn::pistonSpeed() const {
  double p = 0.0;
  for (std::size_t i = 1; i < m_mass.size(); ++i) p += m_mass[i] * m_v[i];
  return p / pistonMass();
}

double ImpactorColumn::momentum() const {
  double p = 0.0;
  for (std::size_t i = 0; i < m_mass.size(); ++i) p += m_mass[i] * m_v[i];
  return p;
}

double ImpactorColumn::kineticEnergy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < m_mass.size(); ++i) e += 0.5 * m_mass[i] * m_v[i] * m_v[i];
  return e;
}

double ImpactorColumn::elasticEnergy() const {
  const double contact = contactForce();  // k_c times the spring's stretch, whichever contact
  double e = 0.5 * contact * contact / m_contactStiffness;
  for (std::size_t i = 1; i + 1 < m_mass.size(); ++i) {
    const double d = m_u[i] - m_u[i + 1];
    e += 0.5 * m_elementStiffness * d * d;
  }
  return e;
}

void ImpactorColumn::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "impactor");
  archive.expectCount("points", m_u.size());
  archive.array("displacement", m_u);
  archive.array("speed", m_v);
  archive.value("face_work", m_faceWork);
}

}  // namespace rupture::fsi
