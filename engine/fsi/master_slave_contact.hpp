#pragma once
// Master–slave contact (Caleyron et al. 2013 §4.3, after Hallquist et al. 1985): the plate is the master
// surface, fluid particles are slaves. For each particle near the plate, the nearest intact node
// says whether there is a surface under it (in-plane distance < R_c; a hole or a crack leaves
// none); the surface around it is the Shepard interpolation of the intact nodes within
// S = 1.5 max(Δ, dx) (weights (1 − ρ/S)²; ContactGeometry::surfaceSupport: the particle's face, so
// that a plate finer than the fluid is pressed, not dimpled): point x̄, normal n̄, velocity v̄.
// A slave closer than t/2 + r_f to it is put back on the offset surface (position projection
// along n̄) and, when approaching, its normal velocity relative to v̄ is cancelled by an impulse J along n̄ (reduced mass of the particle and
// of the surface point, 1/m_M = Σ ŵ_k²/m_k over the nodes' shares); the tangential velocity is
// untouched (frictionless sliding, what Caleyron et al. chose the method for). The nodes receive −ŵ_k J,
// so momentum is conserved exactly, as for the pinballs.
#include "fsi/contact_geometry.hpp"
#include "fsi/contact_outcome.hpp"
#include "fsi/shell_node_grid.hpp"
#include "shell/sph_shell.hpp"
#include "sph/fluid_particles.hpp"

namespace rupture::fsi {

ContactOutcome resolveMasterSlaveContact(sph::FluidParticles& fluid, const SphShell& shell, const ShellNodeGrid& grid,
                                         const ContactGeometry& geometry, double dt);

}  // namespace rupture::fsi
