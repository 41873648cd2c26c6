#pragma once
// Corotational kinematics shared by the rotational bond laws (beams, Born springs): the end tangent
// a node's orientation carries, and the bending rotation taking the current chord onto it. Here in
// core so that every law can include it without reaching into another law's folder.
#include <cmath>

#include "core/fast_math.hpp"

namespace rupture {

/// Rotates v by the unit quaternion (w, ux, uy, uz): v' = v + w t + u × t with t = 2 u × v.
[[gnu::always_inline]] inline void rotateByQuaternion(double w, double ux, double uy, double uz, double vx, double vy,
                               double vz, double& ox, double& oy, double& oz) {
  const double tx = 2.0 * (uy * vz - uz * vy);
  const double ty = 2.0 * (uz * vx - ux * vz);
  const double tz = 2.0 * (ux * vy - uy * vx);
  ox = vx + w * tx + (uy * tz - uz * ty);
  oy = vy + w * ty + (uz * tx - ux * tz);
  oz = vz + w * tz + (ux * ty - uy * tx);
}

/// Bending rotation vector taking the chord n onto the end tangent a (both unit vectors).
[[gnu::always_inline]] inline void bendingRotation(double nx, double ny, double nz, double ax, double ay, double az,
                            double& px, double& py, double& pz) {
  const double cx = ny * az - nz * ay, cy = nz * ax - nx * az, cz = nx * ay - ny * ax;
  const double s = std::sqrt(cx * cx + cy * cy + cz * cz);
  const double c = nx * ax + ny * ay + nz * az;
  const double angle = atan2Branchless(s, c);
  // For an unbent end s = 0 and c = 0: the floor on s avoids 0/0 and gives φ = 0.
  const double scale = angle / (s > 1e-300 ? s : 1e-300);
  px = cx * scale; py = cy * scale; pz = cz * scale;
}

}  // namespace rupture
