#include "bonded/bonded_system.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/parallel.hpp"
#include "core/bond_loop.hpp"
#include "core/central_bond_loop.hpp"

namespace rupture {

namespace {

/// The planar-motion invariant of BondedSystem::planarMotion.
bool movesInPlane(const ParticleStore& p, const BondStore& bonds) {
  if (p.dimension != 2) return false;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.z[k] != p.z[0] || p.qx[k] != 0.0 || p.qy[k] != 0.0 || p.vz[k] != 0.0 || p.wx[k] != 0.0 || p.wy[k] != 0.0)
      return false;
  for (std::size_t b = 0; b < bonds.size(); ++b)
    if (bonds.n0z[b] != 0.0) return false;
  return true;
}

}  // namespace

BondedSystem BondedSystem::withoutElements() const {
  BondedSystem out;
  out.particles.dimension = particles.dimension;
  out.model = model;
  out.beam = beam;
  out.contact = HertzContact(contact.parameters());
  out.prescribe = prescribe;
  out.externalLoads = externalLoads;
  out.refreshGhosts = refreshGhosts;
  out.localDamping = localDamping;
  out.bondDamping = bondDamping;
  out.dampingWaveSpeed = dampingWaveSpeed;
  out.centralLoop = centralLoop;
  out.compactCentralList = compactCentralList;
  out.time = time;
  out.steps = steps;
  out.brokenLastStep = brokenLastStep;
  return out;  // the rest (the damage index, the loop's lists) is initialize's
}

void BondedSystem::initialize() {
  m_loadTime = time;
  m_planar = movesInPlane(particles, bonds);
  if (std::holds_alternative<BeamModel>(model)) {
    // σ_f <= 0 means unbreakable.
    const double sigma = beam.failureStress > 0 ? beam.failureStress : std::numeric_limits<double>::infinity();
    std::fill(bonds.threshold.begin(), bonds.threshold.end(), sigma);
  }
  bonds.finalize(particles.size());
  if (m_planar) {  // the planar bond loop never writes these: they stay 0
    for (auto* v : {&bonds.fjz, &bonds.tix, &bonds.tiy, &bonds.tjx, &bonds.tjy}) std::fill(v->begin(), v->end(), 0.0);
  }
  m_minStretch.assign(particles.size(), 0.0);
  m_minStretchNext.assign(particles.size(), 0.0);
  m_centralCurrent = false;
  m_loadsStale = false;
  m_recordedIntegrity = bonds.intact;
  m_bondedVolume.assign(particles.size(), 0.0);
  m_brokenVolume.assign(particles.size(), 0.0);
  m_damage.assign(particles.size(), 0.0);
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    m_bondedVolume[bonds.i[b]] += partnerVolume(bonds.j[b]);
    m_bondedVolume[bonds.j[b]] += partnerVolume(bonds.i[b]);
  }
  for (std::size_t b = 0; b < bonds.size(); ++b)
    if (m_recordedIntegrity[b] < 1.0) recordDamage(b, 1.0 - m_recordedIntegrity[b]);
  m_previousLength.clear();
  if (bondDamping > 0) {
    m_previousLength.resize(bonds.size());
    for (std::size_t b = 0; b < bonds.size(); ++b) {
      const std::int32_t i = bonds.i[b], j = bonds.j[b];
      const double dx = particles.x[j] - particles.x[i], dy = particles.y[j] - particles.y[i],
                   dz = particles.z[j] - particles.z[i];
      m_previousLength[b] = std::sqrt(dx * dx + dy * dy + dz * dz);
    }
  }
  m_step = 0.0;
  if (refreshGhosts) refreshGhosts(particles, m_minStretch);
  computeLoads();
}

std::size_t BondedSystem::handOverDamagedBonds() {
  // Find the bonds whose integrity just dropped (a parallel scan: each thread keeps its own list,
  // and the lists are joined in thread order, so the order does not depend on timing), add their
  // loss to the damage index and hand the pairs of those that broke to the contact search.
  std::vector<std::vector<std::size_t>> found;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(bonds.size());
#pragma omp parallel if (worthParallel(bonds.size()))
  {
#pragma omp single
    found.resize(omp_get_num_threads());
    std::vector<std::size_t>& mine = found[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (std::ptrdiff_t b = 0; b < n; ++b)
      if (bonds.intact[b] < m_recordedIntegrity[b]) mine.push_back(b);
  }
  std::size_t broken = 0;
  for (const auto& list : found) broken += recordDamagedBonds(list);
  return broken;
}

double BondedSystem::partnerVolume(std::int32_t k) const {
  return particles.volume.size() == particles.size() ? particles.volume[k] : 1.0;
}

void BondedSystem::recordDamage(std::size_t b, double lost) {
  const std::int32_t i = bonds.i[b], j = bonds.j[b];
  m_brokenVolume[i] += lost * partnerVolume(j);
  m_brokenVolume[j] += lost * partnerVolume(i);
  m_damage[i] = m_brokenVolume[i] / m_bondedVolume[i];
  m_damage[j] = m_brokenVolume[j] / m_bondedVolume[j];
}

std::size_t BondedSystem::recordDamagedBonds(const std::vector<std::size_t>& damaged) {
  std::size_t broken = 0;
  for (std::size_t b : damaged) {
    recordDamage(b, m_recordedIntegrity[b] - bonds.intact[b]);
    m_recordedIntegrity[b] = bonds.intact[b];
    if (bonds.intact[b] > 0.0) continue;  // partly damaged: still bonded
    ++broken;
    m_brokenNow.push_back(b);
    contact.onBondBroken(bonds.i[b], bonds.j[b], bonds.restLength[b]);
  }
  return broken;
}

const BondStore& BondedSystem::bondLoads() const {
  if (m_loadsStale) {
    visitModel([&](const auto& law, const auto& criterion) {
      using Law = std::decay_t<decltype(law)>;
      using Criterion = std::decay_t<decltype(criterion)>;
      if constexpr (requires(const Law& l, const BondGeometry& g) { l.planarResponse(g); }) {
        if (m_planar) {  // as the step's loop evaluates them (computeLoads)
          storeBondLoads<Law, Criterion, true>(law, criterion, particles, bonds);
          return;
        }
      }
      storeBondLoads(law, criterion, particles, bonds);
    });
    m_loadsStale = false;
  }
  return bonds;
}

void BondedSystem::computeLoads() {
  bool planarPass = false;
  m_brokenNow.clear();
  visitModel([&](const auto& law, const auto& criterion) {
    using Law = std::decay_t<decltype(law)>;
    using Criterion = std::decay_t<decltype(criterion)>;
    if constexpr (!Law::kRotational) {
      if (centralLoop && bondDamping <= 0 && !bonds.hasFibres()) {
        if (!m_centralCurrent) {
          m_central.build(bonds, compactCentralList);
          m_centralCurrent = true;
        }
        m_broken.clear();
        // One instantiation per storage form of the partner list and per use of the nodal shift.
        auto central = [&](auto compact) {
          constexpr bool kCompact = decltype(compact)::value;
          if constexpr (Criterion::kNodalShift) {
            if (criterion.alpha != 0.0) {
              evaluateCentralBonds<Law, Criterion, true, kCompact>(law, criterion, particles, bonds, m_central,
                                                                   m_minStretch.data(), m_minStretchNext.data(),
                                                                   m_broken);
              m_minStretch.swap(m_minStretchNext);
              return;
            }
          }
          evaluateCentralBonds<Law, Criterion, false, kCompact>(law, criterion, particles, bonds, m_central, nullptr,
                                                                nullptr, m_broken);
        };
        if (m_central.compact)
          central(std::true_type{});
        else
          central(std::false_type{});
        brokenLastStep = recordDamagedBonds(m_broken);
        m_loadsStale = true;
        return;
      }
    }
    m_centralCurrent = false;  // this loop breaks bonds the partner list would not know about
    m_loadsStale = false;
    // One dispatch per pass on the planar form (2D), then the loops are templates.
    auto pass = [&](auto planar) {
      constexpr bool kPlanar = decltype(planar)::value;
      // One instantiation with the fibres of anisotropic damage, one without.
      auto evaluate = [&](auto fibres) -> std::size_t {
        constexpr bool kFibres = decltype(fibres)::value;
        if (bondDamping > 0 && m_step > 0) {
          const SillingDamping damping{bondDamping, 1.0 / (m_step * dampingWaveSpeed), m_damage.data(),
                                       m_previousLength.data()};
          return evaluateBonds<Law, Criterion, true, kPlanar, kFibres>(law, criterion, particles, bonds,
                                                                       m_minStretch.data(), damping);
        }
        return evaluateBonds<Law, Criterion, false, kPlanar, kFibres>(law, criterion, particles, bonds,
                                                                      m_minStretch.data());
      };
      const std::size_t damaged = bonds.hasFibres() ? evaluate(std::true_type{}) : evaluate(std::false_type{});
      brokenLastStep = damaged > 0 ? handOverDamagedBonds() : 0;
      if constexpr (Criterion::kNodalShift) {
        if (criterion.alpha != 0.0) {
          gatherBondLoads<Law::kRotational, true, kPlanar>(bonds, particles, m_minStretch.data());
          return;
        }
      }
      gatherBondLoads<Law::kRotational, false, kPlanar>(bonds, particles, nullptr);
    };
    if constexpr (requires(const Law& l, const BondGeometry& g) { l.planarResponse(g); }) {
      if (m_planar) {
        pass(std::true_type{});
        planarPass = true;
        return;
      }
    }
    pass(std::false_type{});
  });
  contact.addForces(particles, bonds, m_planar);
  if (externalLoads) externalLoads(particles, m_loadTime);
  // After the planar pass the gather wrote f_z = t_x = t_y = 0, 2D contact adds only zeros to them
  // (n_z = 0, no out-of-plane velocity) and the planar kick does not read them: without external
  // loads the fill would be a no-op.
  if (particles.dimension == 2 && !(planarPass && !externalLoads)) {
    // Planar motion: no out-of-plane force, no torque about in-plane axes.
    std::fill(particles.fz.begin(), particles.fz.end(), 0.0);
    std::fill(particles.tx.begin(), particles.tx.end(), 0.0);
    std::fill(particles.ty.begin(), particles.ty.end(), 0.0);
  }
}

namespace {

// v += (dt/2) F/m on the free degrees of freedom. Written with 0/1 factors instead of branches so
// that it vectorises; Cundall damping (quasi-static runs only) is a separate instantiation.
// kPlanar: only v_x, v_y, ω_z (the other loads are 0 in 2D, so the others would not change).
template <bool kDamped, bool kPlanar>
void kickLoop(ParticleStore& p, double halfDt, double gamma) {
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
  const std::uint8_t* fixed = p.fixedDofs.data();
  const double *mass = p.mass.data(), *inertia = p.inertia.data();
  const double *fx = p.fx.data(), *fy = p.fy.data(), *fz = p.fz.data();
  const double *tx = p.tx.data(), *ty = p.ty.data(), *tz = p.tz.data();
  double *vx = p.vx.data(), *vy = p.vy.data(), *vz = p.vz.data();
  double *wx = p.wx.data(), *wy = p.wy.data(), *wz = p.wz.data();
  // Cundall: each load component is reduced by γ|F| against the velocity component.
  auto load = [gamma](double f, double v) {
    if constexpr (kDamped) {
      const double sign = v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
      return f - gamma * std::fabs(f) * sign;
    } else {
      (void)v;
      return f;
    }
  };
#pragma omp parallel for simd schedule(static) if (worthParallel(p.size()))
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const unsigned f = fixed[k];
    const double a = halfDt / mass[k], b = halfDt / inertia[k];
    const double freeX = (f & kFixX) ? 0.0 : a, freeY = (f & kFixY) ? 0.0 : a, freeZ = (f & kFixZ) ? 0.0 : a;
    const double freeR = (f & kFixRotation) ? 0.0 : b;
    vx[k] += freeX * load(fx[k], vx[k]);
    vy[k] += freeY * load(fy[k], vy[k]);
    if constexpr (!kPlanar) {
      vz[k] += freeZ * load(fz[k], vz[k]);
      wx[k] += freeR * load(tx[k], wx[k]);
      wy[k] += freeR * load(ty[k], wy[k]);
    }
    wz[k] += freeR * load(tz[k], wz[k]);
  }
}

// x += dt v and q <- exp(dt/2 ω) q for planar motion: ω = ω_z e_z and q = (w, 0, 0, q_z). The
// operations of the 3D drift with its zero terms left out, in the same order (the same numbers).
void driftPlanar(ParticleStore& p, double dt) {
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
  double *x = p.x.data(), *y = p.y.data(), *qw = p.qw.data(), *qz = p.qz.data();
  const double *vx = p.vx.data(), *vy = p.vy.data(), *wz = p.wz.data();
#pragma omp parallel for simd schedule(static) if (worthParallel(p.size()))
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    x[k] += dt * vx[k];
    y[k] += dt * vy[k];
    const double hz = 0.5 * dt * wz[k];
    const double h2 = hz * hz;
    const double c = 1.0 - h2 / 2.0 + h2 * h2 / 24.0;
    const double s = 1.0 - h2 / 6.0 + h2 * h2 / 120.0;
    const double dw = c, dz = s * hz;
    const double w = qw[k], z = qz[k];
    const double nw = dw * w - dz * z;
    const double nz = dw * z + dz * w;
    const double inv = 1.0 / std::sqrt(nw * nw + nz * nz);
    qw[k] = nw * inv; qz[k] = nz * inv;
  }
}

}  // namespace

void BondedSystem::kick(double halfDt) {
  if (m_planar) {
    if (localDamping > 0) kickLoop<true, true>(particles, halfDt, localDamping);
    else kickLoop<false, true>(particles, halfDt, 0.0);
  } else {
    if (localDamping > 0) kickLoop<true, false>(particles, halfDt, localDamping);
    else kickLoop<false, false>(particles, halfDt, 0.0);
  }
}

void BondedSystem::drift(double dt) {
  if (m_planar) {
    driftPlanar(particles, dt);
    return;
  }
  ParticleStore& p = particles;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
  // Local pointers: through p's vectors GCC reloads each array's address per element and, without
  // AVX-512's scatters, left this loop scalar.
  double *px = p.x.data(), *py = p.y.data(), *pz = p.z.data();
  double *qw = p.qw.data(), *qx = p.qx.data(), *qy = p.qy.data(), *qz = p.qz.data();
  const double *vx = p.vx.data(), *vy = p.vy.data(), *vz = p.vz.data();
  const double *wx = p.wx.data(), *wy = p.wy.data(), *wz = p.wz.data();
#pragma omp parallel for simd schedule(static) if (worthParallel(p.size()))
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    px[k] += dt * vx[k];
    py[k] += dt * vy[k];
    pz[k] += dt * vz[k];
    // q <- exp(dt/2 ω) q, with cos/sin of the half angle by their Taylor series to O(h⁶)
    // (h = |ω| dt / 2 is tiny at a stable step), then renormalised.
    const double hx = 0.5 * dt * wx[k], hy = 0.5 * dt * wy[k], hz = 0.5 * dt * wz[k];
    const double h2 = hx * hx + hy * hy + hz * hz;
    const double c = 1.0 - h2 / 2.0 + h2 * h2 / 24.0;
    const double s = 1.0 - h2 / 6.0 + h2 * h2 / 120.0;
    const double dw = c, dx = s * hx, dy = s * hy, dz = s * hz;
    const double w = qw[k], x = qx[k], y = qy[k], z = qz[k];
    double nw = dw * w - dx * x - dy * y - dz * z;
    double nx = dw * x + dx * w + dy * z - dz * y;
    double ny = dw * y - dx * z + dy * w + dz * x;
    double nz = dw * z + dx * y - dy * x + dz * w;
    const double inv = 1.0 / std::sqrt(nw * nw + nx * nx + ny * ny + nz * nz);
    qw[k] = nw * inv; qx[k] = nx * inv; qy[k] = ny * inv; qz[k] = nz * inv;
  }
}

void BondedSystem::adoptGatheredState(double atTime, std::size_t atSteps) {
  time = atTime;
  steps = atSteps;
  m_loadTime = atTime;
  m_loadsStale = true;
}

void BondedSystem::setParticleCount(std::size_t n, std::size_t bondedCount) {
  if (n < bondedCount || bonds.incidenceStart.size() < bondedCount + 1)
    throw std::logic_error("BondedSystem::setParticleCount: " + std::to_string(n) + " particles would drop bonded ones");
  particles.resize(n);
  // The added particles have no bond: an empty incidence range each.
  const std::int32_t end = bonds.incidenceStart[bondedCount];
  bonds.incidenceStart.resize(n + 1, end);
  for (auto* v : {&m_damage, &m_brokenVolume, &m_bondedVolume, &m_minStretch, &m_minStretchNext})
    if (!v->empty()) v->resize(n, 0.0);
}

void BondedSystem::step(double dt) {
  kick(0.5 * dt);                                  // v(t + dt/2) from F(t)
  if (prescribe) prescribe(particles, time + 0.5 * dt);
  drift(dt);                                       // x(t + dt), q(t + dt)
  if (refreshGhosts) refreshGhosts(particles, m_minStretch);
  m_loadTime = time + dt;
  m_step = dt;
  computeLoads();                                  // F(t + dt); beams may break
  kick(0.5 * dt);                                  // v(t + dt)
  time += dt;
  ++steps;
  if (prescribe) prescribe(particles, time);
}

double BondedSystem::criticalTimeStep() const {
  std::vector<double> kTranslation, kRotation;
  const bool central = visitModel([&](const auto& law, const auto&) {
    accumulateBondStiffness(law, particles, bonds, kTranslation, kRotation);
    return !std::decay_t<decltype(law)>::kRotational;
  });
  // Central forces: the Gershgorin row of the stiffness matrix is 2 Σ k, so ω² <= 2 Σ k / m and
  // dt_c = 2/ω = √(2m / Σ k) (Silling & Askari 2005 for PD). The rotational laws keep √(m / Σ k)
  // (docs/references.md#eq-gershgorin).
  const double factor = central ? 2.0 : 1.0;
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (kTranslation[k] > 0) dt = std::min(dt, std::sqrt(factor * particles.mass[k] / kTranslation[k]));
    if (kRotation[k] > 0) dt = std::min(dt, std::sqrt(particles.inertia[k] / kRotation[k]));
  }
  return dt;
}

std::vector<double> BondedSystem::bondStiffness() const {
  std::vector<double> k(bonds.size(), 0.0);
  visitModel([&](const auto& law, const auto&) {
    using Law = std::decay_t<decltype(law)>;
    for (std::size_t b = 0; b < bonds.size(); ++b)
      k[b] = law.stiffness(bondGeometry<Law>(particles, bonds, b)).translational;
  });
  return k;
}

double BondedSystem::maxFailureRatio() const {
  bondLoads();
  double worst = 0;
  for (std::size_t b = 0; b < bonds.size(); ++b)
    if (bonds.intact[b] > 0.0 && std::isfinite(bonds.failureThreshold[b]) && bonds.failureThreshold[b] > 0)
      worst = std::max(worst, bonds.failureMeasure[b] / (bonds.failureThreshold[b] * bonds.firstDamageFactor(b)));
  return worst;
}

double BondedSystem::kineticEnergy() const {
  const ParticleStore& p = particles;
  double e = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    e += 0.5 * p.mass[k] * (p.vx[k] * p.vx[k] + p.vy[k] * p.vy[k] + p.vz[k] * p.vz[k]);
    e += 0.5 * p.inertia[k] * (p.wx[k] * p.wx[k] + p.wy[k] * p.wy[k] + p.wz[k] * p.wz[k]);
  }
  return e;
}

double BondedSystem::bondEnergy() const {
  return visitModel([&](const auto& law, const auto&) {
    using Law = std::decay_t<decltype(law)>;
    if constexpr (requires(const Law& l, const BondGeometry& g) { l.planarEnergy(g); }) {
      if (m_planar) return rupture::bondEnergy<Law, true>(law, particles, bonds);
    }
    return rupture::bondEnergy(law, particles, bonds);
  });
}

double BondedSystem::elasticEnergy() const { return bondEnergy() + contact.energy(particles); }

void BondedSystem::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "bonded_system");
  particles.exchangeState(archive);
  bonds.exchangeState(archive, std::holds_alternative<BeamModel>(model));
  contact.exchangeState(archive);
  archive.value("time", time);
  archive.value("steps", steps);
  archive.value("broken_last_step", brokenLastStep);
  archive.array("recorded_integrity", m_recordedIntegrity);
  archive.array("damage", m_damage);
  archive.array("broken_volume", m_brokenVolume);
  archive.array("bonded_volume", m_bondedVolume);
  archive.array("previous_length", m_previousLength);
  archive.value("step", m_step);
  archive.array("min_stretch", m_minStretch);
  archive.array("min_stretch_next", m_minStretchNext);
  archive.value("load_time", m_loadTime);
  // The central loop's slot list is a copy of the bonds (their intact flags and thresholds): the
  // next evaluation rebuilds it from them, and refills its packed positions every time.
  if (archive.loading()) m_centralCurrent = false;
  archive.value("loads_stale", m_loadsStale);
  archive.array("broken", m_broken);
  archive.value("planar", m_planar);
}

}  // namespace rupture
