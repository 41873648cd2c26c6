#pragma once
// Born lattice model (Yu et al. 2019; docs/references.md#eq-lattice): a normal spring k_n and a shear spring
// k_s = shearRatio · k_n per bond, U = ½ k_n d_n² + ½ k_s |d_s|².
//
// Rotational invariance (the reference's caveat): d_s is measured against the nodes' own rotations,
// not against the fixed reference direction. Each node carries an orientation q; the bending
// rotation φ_k takes the chord n onto the end tangent a_k = R(q_k) n0 (as for beams, core/corotation.hpp),
// and the shear displacement is d_s = (L0/2)(φ_i + φ_j) × n. A rigid rotation moves chord and
// tangents together (d_s = 0); under a homogeneous strain the node rotations stay zero on the
// centro-symmetric lattices (the torques cancel), so d_s is the classical perpendicular relative
// displacement and the classical energy-equivalence mapping holds.
//   U = ½ k_n (L − L0)² + ½ k_s (L0²/4) |φ_i + φ_j|²
//   T_i = T_j = −k_s (L0²/4)(φ_i + φ_j),   F_j = −k_n (L − L0) n + (k_s L0² / (2L)) (φ_i + φ_j) × n
// (the shear force balances the moments exactly about the chord, as for beams).
#include <cmath>

#include "core/bond_law.hpp"
#include "core/corotation.hpp"

namespace rupture {

struct BornLaw {
  static constexpr const char* kName = "born";
  static constexpr bool kRotational = true;
  double shearRatio = 0.0;  ///< k_s / k_n (1)

  [[gnu::always_inline]] BondResponse response(const BondGeometry& g) const {
    const double length = std::sqrt(g.dx * g.dx + g.dy * g.dy + g.dz * g.dz);
    const double invL = 1.0 / length;
    const double nx = g.dx * invL, ny = g.dy * invL, nz = g.dz * invL;
    double aix, aiy, aiz, ajx, ajy, ajz;
    rotateByQuaternion(g.qiw, g.qix, g.qiy, g.qiz, g.n0x, g.n0y, g.n0z, aix, aiy, aiz);
    rotateByQuaternion(g.qjw, g.qjx, g.qjy, g.qjz, g.n0x, g.n0y, g.n0z, ajx, ajy, ajz);
    double pix, piy, piz, pjx, pjy, pjz;
    bendingRotation(nx, ny, nz, aix, aiy, aiz, pix, piy, piz);
    bendingRotation(nx, ny, nz, ajx, ajy, ajz, pjx, pjy, pjz);
    const double sx = pix + pjx, sy = piy + pjy, sz = piz + pjz;

    const double kn = g.stiffness, ks = shearRatio * g.stiffness;
    const double extension = length - g.restLength;
    const double normal = kn * extension;
    const double kRot = 0.25 * ks * g.restLength * g.restLength;  // k_s L0²/4
    const double shear = 2.0 * kRot * invL;                       // k_s L0² / (2L)
    BondResponse r;
    r.fjx = -normal * nx + shear * (sy * nz - sz * ny);
    r.fjy = -normal * ny + shear * (sz * nx - sx * nz);
    r.fjz = -normal * nz + shear * (sx * ny - sy * nx);
    r.tix = r.tjx = -kRot * sx;
    r.tiy = r.tjy = -kRot * sy;
    r.tiz = r.tjz = -kRot * sz;
    const double normalEnergy = 0.5 * normal * extension;
    r.shearEnergy = 0.5 * kRot * (sx * sx + sy * sy + sz * sz);
    r.energy = normalEnergy + r.shearEnergy;
    r.stretch = extension / g.restLength;
    r.normalForce = normal;
    r.tensileNormalEnergy = extension > 0 ? normalEnergy : 0.0;
    r.equivalentStress = 0.0;
    return r;
  }

  /// Gershgorin rows: translation max(k_n, k_s); rotation k_s L0²/4 on the diagonal plus the same
  /// coupling to the other end.
  BondStiffness stiffness(const BondGeometry& g) const {
    const double ks = shearRatio * g.stiffness;
    return {std::fmax(g.stiffness, ks), 0.5 * ks * g.restLength * g.restLength};
  }
};

}  // namespace rupture
