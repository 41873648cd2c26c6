#pragma once
// Cohesive beam bond (André, Iordanoff, Charles, Néauport, CMAME 213–216, 2012): each bonded pair
// is joined by a cylindrical Euler–Bernoulli beam of Young's modulus E_μ, Poisson ratio ν_μ and
// radius r_μ = radius_ratio × (R_i + R_j)/2, clamped at both element centres, carrying axial force,
// shear force, bending moments and torsion. Failure: Rankine equivalent stress (damage/rankine.hpp).
//
// Corotational kinematics (docs/references.md#eq-beam): n = current chord direction i -> j, L its
// length; a_k = R(q_k) n0 is the beam tangent carried by end k. The bending rotation of end k is the
// rotation vector taking n onto a_k, φ_k = angle(n, a_k) · unit(n × a_k). The twist ψ is the
// twist about n of the relative rotation q_j q_i* (swing–twist decomposition).
// Energy (clamped–clamped beam):
//   U = ½ k_ax (L − L0)² + (2 E I / L0)(φ_i² + φ_i·φ_j + φ_j²) + ½ (G J / L0) ψ²
// Loads (−∂U; the shear force uses 1/(L0 L) so that moments balance exactly about the chord):
//   F_j = −(E S / L0)(L − L0) n + (6 E I / (L0 L)) (φ_i + φ_j) × n,     F_i = −F_j
//   T_i = −(2 E I / L0)(2 φ_i + φ_j) + (G J / L0) ψ n
//   T_j = −(2 E I / L0)(φ_i + 2 φ_j) − (G J / L0) ψ n
// Section: S = π r², I = π r⁴/4, J = π r⁴/2.
#include <cmath>
#include <numbers>
#include <string>

#include "core/corotation.hpp"
#include "core/fast_math.hpp"
#include "damage/rankine.hpp"

namespace rupture {

/// Microscopic beam parameters (SI). Validated once in engine/io (bonded spec parsing).
struct BeamParameters {
  double youngModulus = 0;   ///< E_μ (Pa)
  double poissonRatio = 0.3; ///< ν_μ (1); enters only through G_μ = E_μ / (2(1 + ν_μ))
  double radiusRatio = 0.3;  ///< r_μ / R_DE (1), R_DE = mean radius of the two elements
  double failureStress = 0;  ///< σ_f (Pa), Rankine threshold; <= 0 or infinity: unbreakable
  /// Bending moment in σ_Nmax of eq. (1): false = the larger clamped–clamped end moment (chord
  /// rotation included); true = the pure-bending moment of the two ends' relative rotation,
  /// E I |φ_j − φ_i| / L0 (André et al. 2012's σ = E r |θ_2 − θ_1| / L; see engine/dem/README.md).
  bool bendingFromRelativeRotation = false;

  double shearModulus() const { return youngModulus / (2.0 * (1.0 + poissonRatio)); }
};

/// Section constants of one beam.
struct BeamSection {
  double radius, area, secondMoment, polarMoment;
  static BeamSection of(const BeamParameters& p, double radiusI, double radiusJ) {
    const double r = p.radiusRatio * 0.5 * (radiusI + radiusJ);
    const double r2 = r * r;
    constexpr double pi = std::numbers::pi;
    return {r, pi * r2, 0.25 * pi * r2 * r2, 0.5 * pi * r2 * r2};
  }
};

/// The bending moment of σ_Nmax in eq. (1) from the squared end moments and the squared relative
/// moment ½ |M_j − M_i|: the larger end moment, or with BeamParameters::bendingFromRelativeRotation
/// the relative one (the chord's rotation cancels, only the disks' relative rotation bends the beam).
/// The square is selected, then one root taken: two roots and a select between them made the W1
/// bond loop 2.5 times slower (measured). The flag enters as weights 0 and 1, not as a select: a
/// select on a flag that is the same for every bond kept GCC from vectorising the bond loop without
/// AVX-512 (bench/README.md, W1). w·x + (1 − w)·y is x or y exactly while both are finite.
[[gnu::always_inline]] inline double beamBendingMoment(const BeamParameters& p, double momentI2, double momentJ2,
                                                       double relativeMoment2) {
  const double endMoment2 = momentI2 > momentJ2 ? momentI2 : momentJ2;
  const double relative = p.bendingFromRelativeRotation ? 1.0 : 0.0;
  return std::sqrt(relative * relativeMoment2 + (1.0 - relative) * endMoment2);
}

/// Everything one evaluation of the law produces.
struct BeamResponse {
  double fjx, fjy, fjz;  ///< force on j (N)
  double tix, tiy, tiz;  ///< torque on i (N·m)
  double tjx, tjy, tjz;  ///< torque on j (N·m)
  double equivalentStress;  ///< Rankine σ_eq (Pa)
  double energy;            ///< stored elastic energy U (J)
  double axialForce;        ///< N, tension positive (N)
  double twist;             ///< ψ (rad)
};

/// Evaluates the beam law for one bond. d = x_j − x_i (m); q = (w, x, y, z) orientations.
/// Inline and branch-free so that the bond loop vectorises.
[[gnu::always_inline]] inline BeamResponse beamResponse(const BeamParameters& p, double radiusI, double radiusJ,
                                 double restLength, double n0x, double n0y, double n0z,
                                 double dx, double dy, double dz,
                                 double qiw, double qix, double qiy, double qiz,
                                 double qjw, double qjx, double qjy, double qjz) {
  const BeamSection sec = BeamSection::of(p, radiusI, radiusJ);
  const double invL0 = 1.0 / restLength;
  const double kAxial = p.youngModulus * sec.area * invL0;
  const double kBend = 2.0 * p.youngModulus * sec.secondMoment * invL0;
  const double kTwist = p.shearModulus() * sec.polarMoment * invL0;

  const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
  const double invL = 1.0 / length;
  const double nx = dx * invL, ny = dy * invL, nz = dz * invL;

  // End tangents carried by each element, then the bending rotations relative to the chord.
  double aix, aiy, aiz, ajx, ajy, ajz;
  rotateByQuaternion(qiw, qix, qiy, qiz, n0x, n0y, n0z, aix, aiy, aiz);
  rotateByQuaternion(qjw, qjx, qjy, qjz, n0x, n0y, n0z, ajx, ajy, ajz);
  double pix, piy, piz, pjx, pjy, pjz;
  bendingRotation(nx, ny, nz, aix, aiy, aiz, pix, piy, piz);
  bendingRotation(nx, ny, nz, ajx, ajy, ajz, pjx, pjy, pjz);

  // Twist: relative rotation q_rel = q_j q_i*, twist angle ψ = 2 atan2(v_rel·n, w_rel) with
  // w_rel >= 0 (q and −q are the same rotation).
  const double rw = qjw * qiw + qjx * qix + qjy * qiy + qjz * qiz;
  const double rx = -qjw * qix + qjx * qiw - qjy * qiz + qjz * qiy;
  const double ry = -qjw * qiy + qjx * qiz + qjy * qiw - qjz * qix;
  const double rz = -qjw * qiz - qjx * qiy + qjy * qix + qjz * qiw;
  const double sign = std::copysign(1.0, rw);
  const double twist = 2.0 * atan2Branchless(sign * (rx * nx + ry * ny + rz * nz), sign * rw);

  const double stretch = length - restLength;
  const double axialForce = kAxial * stretch;
  const double sumX = pix + pjx, sumY = piy + pjy, sumZ = piz + pjz;
  const double shear = 3.0 * kBend * invL;  // 6 E I / (L0 L)

  BeamResponse r;
  r.fjx = -axialForce * nx + shear * (sumY * nz - sumZ * ny);
  r.fjy = -axialForce * ny + shear * (sumZ * nx - sumX * nz);
  r.fjz = -axialForce * nz + shear * (sumX * ny - sumY * nx);
  const double twistMoment = kTwist * twist;
  r.tix = -kBend * (2.0 * pix + pjx) + twistMoment * nx;
  r.tiy = -kBend * (2.0 * piy + pjy) + twistMoment * ny;
  r.tiz = -kBend * (2.0 * piz + pjz) + twistMoment * nz;
  const double bjx = -kBend * (pix + 2.0 * pjx), bjy = -kBend * (piy + 2.0 * pjy),
               bjz = -kBend * (piz + 2.0 * pjz);
  r.tjx = bjx - twistMoment * nx;
  r.tjy = bjy - twistMoment * ny;
  r.tjz = bjz - twistMoment * nz;

  // Outer-fibre stresses (Rankine, docs/references.md#eq-rankine): largest end bending moment, torsion.
  const double bix = r.tix - twistMoment * nx, biy = r.tiy - twistMoment * ny,
               biz = r.tiz - twistMoment * nz;
  const double momentI2 = bix * bix + biy * biy + biz * biz;
  const double momentJ2 = bjx * bjx + bjy * bjy + bjz * bjz;
  const double hx = bjx - bix, hy = bjy - biy, hz = bjz - biz;  // ½ |M_j − M_i| = (E I / L0) |φ_j − φ_i|
  const double bendingMoment = beamBendingMoment(p, momentI2, momentJ2, 0.25 * (hx * hx + hy * hy + hz * hz));
  const double normalStress = axialForce / sec.area + bendingMoment * sec.radius / sec.secondMoment;
  const double shearStress = std::fabs(twistMoment) * sec.radius / sec.polarMoment;
  r.equivalentStress = rankineEquivalentStress(normalStress, shearStress);

  const double phiI2 = pix * pix + piy * piy + piz * piz, phiJ2 = pjx * pjx + pjy * pjy + pjz * pjz;
  const double phiIJ = pix * pjx + piy * pjy + piz * pjz;
  r.energy = 0.5 * kAxial * stretch * stretch + kBend * (phiI2 + phiIJ + phiJ2) +
             0.5 * kTwist * twist * twist;
  r.axialForce = axialForce;
  r.twist = twist;
  return r;
}

/// The beam law under planar motion (2D): d_z = n0_z = 0 and both orientations rotations about z,
/// q = (w, 0, 0, q_z). Then the end tangents and the chord stay in the plane, the bending rotations
/// are about z, the twist is exactly 0 and only F_x, F_y, T_z are non-zero. The operations are those
/// of beamResponse with the zero terms left out, in the same order, so the loads are the same
/// numbers (no FMA contraction: the build is ISO C++). The only difference: σ_eq = ½(σ + √(σ²)) is
/// written max(σ, 0), equal unless σ² underflows (|σ| < 1e-154 Pa).
struct PlanarBeamResponse {
  double fjx, fjy;            ///< force on j (N)
  double tiz, tjz;            ///< torques about z on i and j (N·m)
  double equivalentStress;    ///< Rankine σ_eq (Pa)
};

/// In-plane tangent carried by an end: n0 rotated by the z-rotation (w, 0, 0, uz).
[[gnu::always_inline]] inline void rotateInPlane(double w, double uz, double vx, double vy, double& ox, double& oy) {
  const double tx = -(2.0 * (uz * vy));
  const double ty = 2.0 * (uz * vx);
  ox = (vx + w * tx) - uz * ty;
  oy = (vy + w * ty) + uz * tx;
}

/// Bending rotation about z taking the in-plane chord n onto the in-plane tangent a.
[[gnu::always_inline]] inline double bendingRotationInPlane(double nx, double ny, double ax, double ay) {
  const double cz = nx * ay - ny * ax;
  const double s = std::fabs(cz);  // √(c_z²) of the 3D form, exactly
  const double c = nx * ax + ny * ay;
  const double angle = atan2Branchless(s, c);
  return cz * (angle / (s > 1e-300 ? s : 1e-300));
}

/// The planar beam's state, shared by its loads and its energy: stiffnesses, chord and the two end
/// rotations about z relative to the chord.
struct PlanarBeamState {
  BeamSection section;
  double kAxial, kBend;  ///< E S / L0 (N/m), 2 E I / L0 (N·m)
  double length, invL;   ///< current chord length (m) and its inverse
  double nx, ny;         ///< chord direction
  double piz, pjz;       ///< bending rotations of ends i and j (rad)
};

[[gnu::always_inline]] inline PlanarBeamState planarBeamState(const BeamParameters& p, double radiusI, double radiusJ,
                                                              double restLength, double n0x, double n0y, double dx,
                                                              double dy, double qiw, double qiz, double qjw,
                                                              double qjz) {
  PlanarBeamState st;
  st.section = BeamSection::of(p, radiusI, radiusJ);
  const double invL0 = 1.0 / restLength;
  st.kAxial = p.youngModulus * st.section.area * invL0;
  st.kBend = 2.0 * p.youngModulus * st.section.secondMoment * invL0;
  st.length = std::sqrt(dx * dx + dy * dy);
  st.invL = 1.0 / st.length;
  st.nx = dx * st.invL;
  st.ny = dy * st.invL;
  double aix, aiy, ajx, ajy;
  rotateInPlane(qiw, qiz, n0x, n0y, aix, aiy);
  rotateInPlane(qjw, qjz, n0x, n0y, ajx, ajy);
  st.piz = bendingRotationInPlane(st.nx, st.ny, aix, aiy);
  st.pjz = bendingRotationInPlane(st.nx, st.ny, ajx, ajy);
  return st;
}

[[gnu::always_inline]] inline PlanarBeamResponse planarBeamResponse(const BeamParameters& p, double radiusI,
                                                                     double radiusJ, double restLength, double n0x,
                                                                     double n0y, double dx, double dy, double qiw,
                                                                     double qiz, double qjw, double qjz) {
  const PlanarBeamState st = planarBeamState(p, radiusI, radiusJ, restLength, n0x, n0y, dx, dy, qiw, qiz, qjw, qjz);
  const BeamSection& sec = st.section;
  const double axialForce = st.kAxial * (st.length - restLength);
  const double sumZ = st.piz + st.pjz;
  const double shear = 3.0 * st.kBend * st.invL;

  PlanarBeamResponse r;
  r.fjx = -axialForce * st.nx - shear * (sumZ * st.ny);
  r.fjy = -axialForce * st.ny + shear * (sumZ * st.nx);
  r.tiz = -st.kBend * (2.0 * st.piz + st.pjz);
  r.tjz = -st.kBend * (st.piz + 2.0 * st.pjz);

  const double momentI2 = r.tiz * r.tiz, momentJ2 = r.tjz * r.tjz;
  const double hz = r.tjz - r.tiz;
  const double bendingMoment = beamBendingMoment(p, momentI2, momentJ2, 0.25 * (hz * hz));
  const double normalStress = axialForce / sec.area + bendingMoment * sec.radius / sec.secondMoment;
  r.equivalentStress = normalStress > 0 ? normalStress : 0.0;  // Rankine without shear
  return r;
}

/// The elastic energy U of beamResponse under planar motion (twist 0, bending rotations about z),
/// with the zero terms left out: the same number to rounding, for the energy records of 2D runs
/// without the 3D response's quaternion algebra.
[[gnu::always_inline]] inline double planarBeamEnergy(const BeamParameters& p, double radiusI, double radiusJ,
                                                      double restLength, double n0x, double n0y, double dx, double dy,
                                                      double qiw, double qiz, double qjw, double qjz) {
  const PlanarBeamState st = planarBeamState(p, radiusI, radiusJ, restLength, n0x, n0y, dx, dy, qiw, qiz, qjw, qjz);
  const double stretch = st.length - restLength;
  return 0.5 * st.kAxial * stretch * stretch + st.kBend * (st.piz * st.piz + st.piz * st.pjz + st.pjz * st.pjz);
}

}  // namespace rupture
