#include "fsi/piston_drive.hpp"

namespace rupture::fsi {

PistonDrive::PistonDrive(sph::SphSystem& fluid, std::int32_t body, const ImpactorSpec& spec, double areaScale)
    : m_fluid(fluid), m_body(body), m_areaScale(areaScale),
      m_column(spec, fluid.bodies[body].along(fluid.model.gravity)) {
  sph::RigidBody& b = fluid.bodies[body];
  b.motion = sph::BodyMotion::Driven;
  b.speed = m_column.faceSpeed();  // the piston is at rest when the carriage strikes it
}

void PistonDrive::beforeFluidStep(double dt) {
  sph::RigidBody& b = m_fluid.bodies[m_body];
  // The fluid's mean force over the last step: its impulse then (trapezoidal in the body's forces
  // at the step's two ends); before the first step, the force of the initial state.
  const double impulse = b.along(b.impulse), elapsed = m_fluid.time - m_lastTime;
  const double faceForce = m_areaScale * (elapsed > 0 ? (impulse - m_lastImpulse) / elapsed : b.axialForce());
  m_lastImpulse = impulse;
  m_lastTime = m_fluid.time;
  const double start = m_column.faceDisplacement();
  m_column.advance(dt, faceForce);
  b.speed = (m_column.faceDisplacement() - start) / dt;
}

void PistonDrive::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "piston_drive");
  m_column.exchangeState(archive);
  archive.value("last_impulse", m_lastImpulse);
  archive.value("last_time", m_lastTime);
}

}  // namespace rupture::fsi
