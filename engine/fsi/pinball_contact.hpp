#pragma once
// Pinball contact between SPH fluid particles and shell nodes (Caleyron et al. 2013 §4.3, eqs. 6–7; Belytschko
// & Neal 1991): every (particle, node) pair whose pinballs interpenetrate (contact_geometry.hpp)
// receives an impulse along the node's normal n that cancels the normal relative approach speed,
//   σ (v_f − v_n)·n ≥ 0,  σ = sign((x_f − x_n)·n)
// (the Lagrange-multiplier form of eq. 7), and is put back on the pinball's surface along σ n
// (|s| = t/2 + r_f: cancelling the speed alone lets a loaded particle creep in by a dt²/2 per
// step; a velocity bias that pushes it out instead made the contact chatter). Impulse J = −μ u
// with μ the reduced mass of the particle and its share of the node (m_n over the node's
// contact count: several particles pressing on one node share its inertia; a clamped node is
// immovable). The particle's velocity changes by σ J n / m_f at once
// (pairs of one particle in turn, Gauss–Seidel, so two pinballs do not push it twice); the node
// receives −σ J n in ContactOutcome::impulse, delivered by the coupler as a force over the next
// step, so fluid + plate momentum is conserved exactly.
#include "fsi/contact_geometry.hpp"
#include "fsi/contact_outcome.hpp"
#include "fsi/shell_node_grid.hpp"
#include "shell/sph_shell.hpp"
#include "sph/fluid_particles.hpp"

namespace rupture::fsi {

ContactOutcome resolvePinballContact(sph::FluidParticles& fluid, const SphShell& shell, const ShellNodeGrid& grid,
                                     const ContactGeometry& geometry, double dt);

}  // namespace rupture::fsi
