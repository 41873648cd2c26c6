#pragma once
// A rigid body made of boundary particles (walls, bottoms, pistons), guided along one axis.
// Its particles take part in the pair loop like fluid particles, but move with the body; the force
// the fluid exerts on it is the sum of m·a over its particles, which by the symmetric momentum
// equation is exactly the opposite of the force it exerts on the fluid. Motions:
//   fixed       at rest (tank walls)
//   prescribed  speed along the axis from a piecewise-linear history (held constant past its ends)
//   free        mass M, decelerated or driven by the fluid force and gravity along the axis
//   driven      moves at the speed its owner sets before each step (a structure integrated
//               outside the fluid, such as the elastic piston of fsi/impactor_column.hpp, which
//               reads the body's force back)
// This is the coupling interface a structure uses later: its boundary particles' positions and
// velocities are set from outside and the per-particle fluid force m·a is read back.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rupture::sph {

enum class BodyMotion { Fixed, Prescribed, Free, Driven };

inline std::string toString(BodyMotion m) {
  switch (m) {
    case BodyMotion::Fixed: return "fixed";
    case BodyMotion::Prescribed: return "prescribed";
    case BodyMotion::Free: return "free";
    case BodyMotion::Driven: return "driven";
  }
  return "fixed";
}

/// Speed (m/s) against time (s), linear between points, constant outside them.
struct SpeedHistory {
  std::vector<double> time, speed;
  double at(double t) const {
    if (time.empty()) return 0.0;
    if (t <= time.front()) return speed.front();
    for (std::size_t k = 1; k < time.size(); ++k)
      if (t <= time[k]) return speed[k - 1] + (speed[k] - speed[k - 1]) * (t - time[k - 1]) / (time[k] - time[k - 1]);
    return speed.back();
  }
};

struct RigidBody {
  std::string name;
  BodyMotion motion = BodyMotion::Fixed;
  std::array<double, 3> axis{0, 0, 1};  ///< unit direction of the motion and of `speed`
  double mass = 0;                      ///< kg (kg/m in 2D); free bodies only
  SpeedHistory history;                 ///< prescribed bodies only

  // State, along the axis: speed (m/s) and displacement from the start (m). A driven body's
  // owner sets `speed` before each step: the body drifts dt × speed in it.
  double speed = 0, displacement = 0;
  /// The fluid's force on the body (N; N/m in 2D) and its time integral (N·s).
  std::array<double, 3> force{0, 0, 0}, impulse{0, 0, 0};
  /// Indices of its particles in the store (refreshed whenever the store is reordered).
  std::vector<std::int32_t> members;

  /// A vector's component along the axis (the force's, the impulse's, gravity's).
  double along(const std::array<double, 3>& v) const { return v[0] * axis[0] + v[1] * axis[1] + v[2] * axis[2]; }
  double axialForce() const { return along(force); }
};

}  // namespace rupture::sph
