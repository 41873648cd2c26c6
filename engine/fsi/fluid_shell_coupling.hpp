#pragma once
// Time stepping of SPH water against an SPH shell (docs/fsi-contact.md, "Coupled step"). One
// coupled step of the fluid's size dt:
//   1. the shell is sub-cycled to t + dt (SphShell::advanceInterval: n = ⌈dt / dt_shell⌉ equal
//      steps, or with plate subcycling fine steps in which each node's terms fire at their own
//      class's rate), each node loaded by the constant force I_n / dt, I_n the impulse the fluid
//      gave it at the end of the last step: the plate receives exactly I_n over the step;
//   2. the fluid makes its kick–drift–kick step to t + dt (SphSystem::step), not seeing the plate;
//   3. the contact (pinball or master–slave) corrects the fluid velocities (and positions, for
//      master–slave) against the plate at t + dt and records the new impulses I_n.
// Fluid momentum + shell momentum + the pending impulses is thus conserved by the contact to
// round-off; clamped nodes pass their share to the clamp (the reaction).
#include <array>
#include <cstddef>
#include <vector>

#include "fsi/contact_geometry.hpp"
#include "fsi/contact_method.hpp"
#include "fsi/contact_outcome.hpp"
#include "fsi/shell_node_grid.hpp"
#include "shell/sph_shell.hpp"
#include "sph/sph_system.hpp"

namespace rupture::fsi {

class FluidShellCoupling {
public:
  FluidShellCoupling(sph::SphSystem& fluid, SphShell& shell, ContactMethod method, const ContactGeometry& geometry);

  /// One coupled step of size dt (s). Call fluid.initialise() before the first.
  void step(double dt);

  /// The contact alone, at the current state (the coupler's third stage; tests call it directly).
  const ContactOutcome& resolveContact(double dt);

  /// The last contact's impulses, the forces, the step counters and the timings (docs/checkpoints.md);
  /// the fluid and the shell list their own.
  void exchangeState(StateArchive& archive);

  ContactMethod method() const { return m_method; }
  const ContactGeometry& geometry() const { return m_geometry; }
  /// The fluid's force on the plate over the last step, Σ_n I_n / dt (N), clamped nodes included.
  std::array<double, 3> plateForce() const { return m_plateForce; }
  /// The same over the nodes that are not clamped (N): what bends the plate.
  std::array<double, 3> freePlateForce() const { return m_freePlateForce; }
  /// Impulses (N s) of the last contact, per node: applied over the next step.
  const std::vector<std::array<double, 3>>& pendingImpulse() const { return m_last.impulse; }
  std::size_t contactPairs() const { return m_last.pairs; }
  int lastSubcycles() const { return m_subcycles; }
  std::size_t shellSteps() const { return m_shellSteps; }
  /// Wall-clock seconds spent so far in the fluid's steps, the shell's sub-cycles and the contact
  /// (the benchmark's split, bench/README.md).
  struct Timings { double fluid = 0, shell = 0, contact = 0; };
  const Timings& timings() const { return m_timings; }

private:
  sph::SphSystem& m_fluid;
  SphShell& m_shell;
  ContactMethod m_method;
  ContactGeometry m_geometry;
  ShellNodeGrid m_grid;
  ContactOutcome m_last;
  double m_lastDt = 0;
  std::array<double, 3> m_plateForce{0, 0, 0}, m_freePlateForce{0, 0, 0};
  int m_subcycles = 0;
  std::size_t m_shellSteps = 0;
  Timings m_timings;
};

}  // namespace rupture::fsi
