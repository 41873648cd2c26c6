#pragma once
// Couples the impactor column (impactor_column.hpp) to the SPH piston: the piston's boundary
// particles are a driven body (sph/rigid_body.hpp) that moves with the column's wetted face, and
// the face is pushed back by the force the fluid gave those particles. One fluid step of size dt:
//   1. the column advances to t + dt, sub-cycled, under the fluid's mean force over the last step
//      (its impulse over that step / its length), scaled from the lattice's section to the real
//      bore (the column carries real masses);
//   2. the body's speed for the step is the face's displacement over it / dt, so the SPH piston is
//      where the face is at t + dt; the fluid then steps (the caller's), seeing it there.
// The lag of one step in the face force is the same explicit staggering as the shell's
// (fluid_shell_coupling.hpp). It is stable while the face point's mass ρ A ℓ/2 outweighs the water
// it sets moving in a step, ρ0 c0 A dt: about 20 times at the defaults (20 elements of a 100 mm
// steel piston, ℓ = 5 mm; dx = 4 mm, dt ≈ 0.7 µs), 10 times at the seed's dx = 2 mm.
#include <cstdint>

#include "fsi/impactor_column.hpp"
#include "sph/sph_system.hpp"

namespace rupture::fsi {

class PistonDrive {
public:
  /// body: the piston's index in fluid.bodies (its axis the motion); areaScale: the real bore's
  /// area over the lattice section the body covers. Sets the body to driven; call before
  /// fluid.initialise().
  PistonDrive(sph::SphSystem& fluid, std::int32_t body, const ImpactorSpec& spec, double areaScale);

  /// Stage 1 and 2 above: call before the fluid's step of size dt (s).
  void beforeFluidStep(double dt);

  const ImpactorColumn& column() const { return m_column; }

  /// The column's state and the body's impulse at the last step (docs/checkpoints.md).
  void exchangeState(StateArchive& archive);

private:
  sph::SphSystem& m_fluid;
  std::int32_t m_body;
  double m_areaScale;
  ImpactorColumn m_column;
  double m_lastImpulse = 0;   ///< the body's axial impulse (N s, lattice) when the last step began
  double m_lastTime = 0;      ///< s, when the last step began
};

}  // namespace rupture::fsi
