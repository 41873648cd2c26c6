#include "fsi/fluid_shell_coupling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "fsi/master_slave_contact.hpp"
#include "fsi/pinball_contact.hpp"

namespace rupture::fsi {

FluidShellCoupling::FluidShellCoupling(sph::SphSystem& fluid, SphShell& shell, ContactMethod method,
                                       const ContactGeometry& geometry)
    : m_fluid(fluid), m_shell(shell), m_method(method), m_geometry(geometry) {
  m_last.impulse.assign(shell.size(), {0.0, 0.0, 0.0});
}

const ContactOutcome& FluidShellCoupling::resolveContact(double dt) {
  m_grid.build(m_shell, m_method == ContactMethod::Pinball ? m_geometry.reach() : m_geometry.surfaceReach());
  m_last = m_method == ContactMethod::Pinball
               ? resolvePinballContact(m_fluid.particles, m_shell, m_grid, m_geometry, dt)
               : resolveMasterSlaveContact(m_fluid.particles, m_shell, m_grid, m_geometry, dt);
  m_lastDt = dt;
  m_plateForce = m_freePlateForce = {0.0, 0.0, 0.0};
  for (std::size_t n = 0; n < m_shell.size(); ++n)
    for (int a = 0; a < 3; ++a) {
      m_plateForce[a] += m_last.impulse[n][a] / dt;
      if (!m_shell.clamped(n)) m_freePlateForce[a] += m_last.impulse[n][a] / dt;
    }
  return m_last;
}

void FluidShellCoupling::step(double dt) {
  // 1. The shell to t + dt under the impulses of the last contact, spread over this step.
  for (std::size_t n = 0; n < m_shell.size(); ++n) {
    const auto& I = m_last.impulse[n];
    m_shell.setExternalForce(n, {I[0] / dt, I[1] / dt, I[2] / dt});
  }
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  m_subcycles = static_cast<int>(m_shell.advanceInterval(dt));
  m_shellSteps += static_cast<std::size_t>(m_subcycles);
  const auto shellDone = Clock::now();
  // 2. The fluid; 3. the contact at t + dt.
  m_fluid.step(dt);
  const auto fluidDone = Clock::now();
  resolveContact(dt);
  m_timings.shell += std::chrono::duration<double>(shellDone - start).count();
  m_timings.fluid += std::chrono::duration<double>(fluidDone - shellDone).count();
  m_timings.contact += std::chrono::duration<double>(Clock::now() - fluidDone).count();
}

void FluidShellCoupling::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "coupling");
  archive.value("pairs", m_last.pairs), archive.value("particles", m_last.particles);
  archive.records("impulse", m_last.impulse);
  archive.value("last_dt", m_lastDt);
  archive.record("plate_force", m_plateForce), archive.record("free_plate_force", m_freePlateForce);
  archive.value("subcycles", m_subcycles);
  archive.value("shell_steps", m_shellSteps);
  archive.record("timings", m_timings);
}

}  // namespace rupture::fsi
