#include "sph/sph_system.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/parallel.hpp"

namespace rupture::sph {

namespace {

double bodyAcceleration(const RigidBody& b, const FluidModel& m) {
  if (b.motion != BodyMotion::Free) return 0.0;
  return b.axialForce() / b.mass + b.along(m.gravity);
}

}  // namespace

void SphSystem::refreshMembers() {
  for (RigidBody& b : bodies) b.members.clear();
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const std::int32_t b = particles.body[k];
    if (b == kFluid) continue;
    if (b < 0 || static_cast<std::size_t>(b) >= bodies.size())
      throw std::logic_error("SphSystem: particle of body " + std::to_string(b) + " but only " +
                             std::to_string(bodies.size()) + " bodies");
    bodies[b].members.push_back(static_cast<std::int32_t>(k));
  }
}

void SphSystem::rebuildLists() {
  const double cutoff = model.kernel().support() + listSkin();
  if (m_builds % static_cast<std::size_t>(std::max(1, sortEvery)) == 0) {
    cancel.throwIfRequested();
    const std::vector<std::int32_t>& order = m_list.cellOrder(particles, model.dimension, 0.5 * cutoff);
    cancel.throwIfRequested();
    particles.permute(order, m_permuteScratch, m_permuteIndexScratch);
    refreshMembers();
  }
  cancel.throwIfRequested();
  m_list.build(particles, model.dimension, cutoff, cancel);
  cancel.throwIfRequested();
  std::vector<char> moves(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) moves[b] = bodies[b].motion != BodyMotion::Fixed;
  m_relativeMove.reset(particles, model.dimension, cutoff, moves);
  m_skinBudget = listSkin();  // nothing has moved: the whole skin is left
  // The positions the moves are measured from.
  const std::size_t n = particles.size();
  m_x0.resize(n);
  m_y0.resize(n);
  m_z0.resize(n);
#pragma omp parallel for schedule(static) if (worthParallel(n))
  for (std::size_t k = 0; k < n; ++k) {
    m_x0[k] = particles.x[k];
    m_y0[k] = particles.y[k];
    m_z0[k] = particles.z[k];
  }
  ++m_builds;
}

void SphSystem::evaluateRates(double halfKick) {
  m_forces.resize(bodies.size());
  m_workspace.cancel = cancel;
  m_extremes = computeRates(particles, m_list, model, m_workspace, {halfKick, m_forces});
  cancel.throwIfRequested();  // chunks were skipped: the rates and the kick are not for use
  // The impulse over the step, trapezoid as the fluid's kicks: the force at t is still in place.
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (int a = 0; a < 3; ++a) bodies[b].impulse[a] += halfKick * (bodies[b].force[a] + m_forces[b][a]);
    bodies[b].force = m_forces[b];
  }
}

void SphSystem::setBodyVelocities(bool fixedToo) {
  for (const RigidBody& b : bodies) {
    if (b.motion == BodyMotion::Fixed && !fixedToo) continue;  // zero since initialise
    const double vx = b.speed * b.axis[0], vy = b.speed * b.axis[1], vz = b.speed * b.axis[2];
    const std::int32_t* ids = b.members.data();
#pragma omp parallel for schedule(static) if (worthParallel(b.members.size()))
    for (std::size_t q = 0; q < b.members.size(); ++q) {
      const std::int32_t k = ids[q];
      particles.vx[k] = vx;
      particles.vy[k] = vy;
      particles.vz[k] = vz;
    }
  }
}

void SphSystem::initialise() {
  for (RigidBody& b : bodies) {
    if (b.motion == BodyMotion::Prescribed) b.speed = b.history.at(time);
    if (b.motion == BodyMotion::Fixed) b.speed = 0;
    if (b.motion == BodyMotion::Free && !(b.mass > 0))
      throw std::invalid_argument("SphSystem: free body '" + b.name + "' needs a mass > 0");
  }
  refreshMembers();
  setBodyVelocities(true);
  particles.vxEst = particles.vx;
  particles.vyEst = particles.vy;
  particles.vzEst = particles.vz;
  particles.rhoEst = particles.rho;
  m_builds = 0;
  rebuildLists();
  cancel.throwIfRequested();
  evaluateRates(0.0);
}

void SphSystem::step(double dt) {
  FluidParticles& p = particles;
  const std::size_t n = p.size();
  const double half = 0.5 * dt;
  const double gx = model.gravity[0], gy = model.gravity[1], gz = model.gravity[2];

  // 1. Half kick of v and ρ with the rates at t; drift of x with the half-step velocity; estimates
  //    of v and ρ at t + dt for the pair loop. The largest move since the last list build is taken
  //    here and in the bodies' loop below, not by a pass of its own.
  //    Dynamic: the loop's work is the fluid's, and in cell order the fluid is not spread evenly
  //    (a collapsing column leaves the upper cells to the walls).
  double maxMove2 = 0, maxSpeed2 = 0;
#pragma omp parallel for schedule(dynamic, 4096) reduction(max : maxMove2, maxSpeed2) if (worthParallel(n))
  for (std::size_t k = 0; k < n; ++k) {
    if (p.body[k] == kFluid) {
      const double ax = p.ax[k] + gx, ay = p.ay[k] + gy, az = p.az[k] + gz;
      p.vx[k] += half * ax; p.vy[k] += half * ay; p.vz[k] += half * az;
      p.rho[k] += half * p.drho[k];
      p.x[k] += dt * p.vx[k]; p.y[k] += dt * p.vy[k]; p.z[k] += dt * p.vz[k];
      p.vxEst[k] = p.vx[k] + half * ax; p.vyEst[k] = p.vy[k] + half * ay; p.vzEst[k] = p.vz[k] + half * az;
      p.rhoEst[k] = p.rho[k] + half * p.drho[k];
      const double dx = p.x[k] - m_x0[k], dy = p.y[k] - m_y0[k], dz = p.z[k] - m_z0[k];
      maxMove2 = std::max(maxMove2, dx * dx + dy * dy + dz * dz);
      maxSpeed2 = std::max(maxSpeed2, p.vx[k] * p.vx[k] + p.vy[k] * p.vy[k] + p.vz[k] * p.vz[k]);
    }  // boundary densities are extrapolated from the fluid in computeRates
  }
  // 2. Bodies: the same kick–drift for their one degree of freedom. A fixed body's members keep
  //    their place and zero velocities (set by initialise), and have not moved since the last build.
  for (RigidBody& b : bodies) {
    if (b.motion == BodyMotion::Fixed) continue;
    double estimate = 0;
    if (b.motion == BodyMotion::Free) {
      const double acc = bodyAcceleration(b, model);
      b.speed += half * acc;
      estimate = b.speed + half * acc;
    } else if (b.motion == BodyMotion::Prescribed) {
      b.speed = b.history.at(time + half);  // midpoint: exact displacement for linear histories
      estimate = b.history.at(time + dt);
    } else {
      estimate = b.speed;  // driven: its owner's speed over the step
    }
    const double dx = dt * b.speed;
    b.displacement += dx;
    maxSpeed2 = std::max(maxSpeed2, b.speed * b.speed);
    const std::int32_t* ids = b.members.data();
    double bodyMove2 = 0;
#pragma omp parallel for schedule(static) reduction(max : bodyMove2) if (worthParallel(b.members.size()))
    for (std::size_t q = 0; q < b.members.size(); ++q) {
      const std::int32_t k = ids[q];
      p.x[k] += dx * b.axis[0]; p.y[k] += dx * b.axis[1]; p.z[k] += dx * b.axis[2];
      p.vxEst[k] = estimate * b.axis[0]; p.vyEst[k] = estimate * b.axis[1]; p.vzEst[k] = estimate * b.axis[2];
      const double mx = p.x[k] - m_x0[k], my = p.y[k] - m_y0[k], mz = p.z[k] - m_z0[k];
      bodyMove2 = std::max(bodyMove2, mx * mx + my * my + mz * mz);
    }
    maxMove2 = std::max(maxMove2, bodyMove2);
  }
  time += dt;
  ++steps;

  // 3. Neighbour lists, when two particles that interact may have moved towards each other by more
  //    than the skin since the last build. Three tests, cheapest first; the list is complete if
  //    - every particle has moved less than half the skin since the build; or
  //    - the budget left by the last bound still covers this step: a pair closer than the cutoff
  //      at that bound's step has since changed its relative displacement by at most twice the
  //      largest move of a particle, summed over the steps (the speeds here), and a pair farther
  //      than the cutoff then cannot have come within the support without using up a skin; or
  //    - the bound over the pairs closer than the cutoff now is within the skin
  //      (relative_displacement.hpp), which sets a new budget.
  const double skin = listSkin();
  m_skinBudget -= 2.0 * dt * std::sqrt(maxSpeed2);
  if (maxMove2 > 0.25 * skin * skin && m_skinBudget < 0.0) {
    const double bound = m_relativeMove.evaluate(p, m_x0, m_y0, m_z0);
    if (bound > skin * (1.0 - 1e-9)) rebuildLists();
    else m_skinBudget = skin - bound;
  }

  // 4. Rates at t + dt, with the fluid's second half kick done as they are stored (RateClosing);
  //    the bodies' forces and impulses.
  evaluateRates(half);
  if (!std::isfinite(m_extremes.maxDensity) || !std::isfinite(m_extremes.maxAcceleration))
    throw std::runtime_error("SPH: the solution became non-finite at t = " + std::to_string(time) +
                             " s (time step too large for the sound speed?)");

  // 5. The bodies' second half kick.
  for (RigidBody& b : bodies) {
    if (b.motion == BodyMotion::Free) b.speed += half * bodyAcceleration(b, model);
    else if (b.motion == BodyMotion::Prescribed) b.speed = b.history.at(time);
  }
  setBodyVelocities(false);
}

double SphSystem::stableTimeStep(double courant) const {
  const double h = model.h();
  const double force = m_extremes.maxAcceleration > 0 ? std::sqrt(h / m_extremes.maxAcceleration) : 1e300;
  const double cMax = model.eos.localSoundSpeed(std::max(m_extremes.maxDensity, model.eos.referenceDensity));
  const double acoustic = h / (cMax + m_extremes.maxViscousMu);
  return courant * std::min(force, acoustic);
}

double SphSystem::fluidMass() const {
  double m = 0;
  for (std::size_t k = 0; k < particles.size(); ++k)
    if (particles.isFluid(k)) m += particles.mass[k];
  return m;
}

double SphSystem::kineticEnergy() const {
  const FluidParticles& p = particles;
  double e = 0;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.isFluid(k)) e += 0.5 * p.mass[k] * (p.vx[k] * p.vx[k] + p.vy[k] * p.vy[k] + p.vz[k] * p.vz[k]);
  return e;
}

double SphSystem::potentialEnergy() const {
  const FluidParticles& p = particles;
  const auto& g = model.gravity;
  double e = 0;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.isFluid(k)) e -= p.mass[k] * (g[0] * p.x[k] + g[1] * p.y[k] + g[2] * p.z[k]);
  return e;
}

std::array<double, 3> SphSystem::fluidMomentum() const {
  const FluidParticles& p = particles;
  std::array<double, 3> m{0, 0, 0};
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.isFluid(k)) {
      m[0] += p.mass[k] * p.vx[k];
      m[1] += p.mass[k] * p.vy[k];
      m[2] += p.mass[k] * p.vz[k];
    }
  return m;
}

double SphSystem::probePressure(double px, double py, double pz) const {
  const FluidParticles& p = particles;
  const CubicSplineKernel kernel = model.kernel();
  const double support2 = kernel.support() * kernel.support();
  const bool is3d = model.dimension == 3;
  double weighted = 0, weights = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!p.isFluid(k)) continue;
    const double dx = px - p.x[k], dy = py - p.y[k], dz = is3d ? pz - p.z[k] : 0.0;
    const double r2 = dx * dx + dy * dy + dz * dz;
    if (r2 >= support2) continue;
    const double w = kernel.value(std::sqrt(r2)) * p.mass[k] / p.rho[k];
    weighted += w * model.eos.pressure(p.rho[k]);
    weights += w;
  }
  return weights > 0 ? weighted / weights : 0.0;
}

void SphSystem::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "sph_system");
  particles.exchangeState(archive);
  archive.expectCount("bodies", bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    StateGroup body(archive, "body_" + std::to_string(b));
    RigidBody& rb = bodies[b];
    archive.value("speed", rb.speed), archive.value("displacement", rb.displacement);
    archive.record("force", rb.force), archive.record("impulse", rb.impulse);
    archive.array("members", rb.members);
  }
  archive.value("time", time);
  archive.value("steps", steps);
  archive.record("extremes", m_extremes);
  archive.array("x0", m_x0), archive.array("y0", m_y0), archive.array("z0", m_z0);
  archive.value("builds", m_builds);
  archive.value("skin_budget", m_skinBudget);
  if (!archive.loading()) return;
  // The list and the displacement bound as the last build made them: at the positions of then.
  std::swap(particles.x, m_x0), std::swap(particles.y, m_y0), std::swap(particles.z, m_z0);
  const double cutoff = model.kernel().support() + listSkin();
  m_list.build(particles, model.dimension, cutoff, cancel);
  std::vector<char> moves(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) moves[b] = bodies[b].motion != BodyMotion::Fixed;
  m_relativeMove.reset(particles, model.dimension, cutoff, moves);
  std::swap(particles.x, m_x0), std::swap(particles.y, m_y0), std::swap(particles.z, m_z0);
}

}  // namespace rupture::sph
