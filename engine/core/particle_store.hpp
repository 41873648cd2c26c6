#pragma once
// Structure-of-arrays storage for rigid particles (2D disks or 3D spheres).
// Particles are never reordered after a sample is built (permute is for the builder), so a particle's index is its id:
// bonds and snapshots can refer to indices without a tag/rtag map.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rupture/state_archive.hpp"

namespace rupture {

/// Degrees of freedom whose velocity is prescribed by a scenario instead of integrated.
enum FixedDof : std::uint8_t {
  kFixX = 1,
  kFixY = 2,
  kFixZ = 4,
  kFixRotation = 8,
};

struct ParticleStore {
  int dimension = 3;  ///< 2: motion in the x-y plane, rotation about z only

  // Kinematics (m, m/s, unit quaternion, rad/s) and accumulated loads (N, N·m).
  std::vector<double> x, y, z;
  std::vector<double> vx, vy, vz;
  std::vector<double> fx, fy, fz;
  std::vector<double> qw, qx, qy, qz;
  std::vector<double> wx, wy, wz;
  std::vector<double> tx, ty, tz;

  // Constant properties: radius (m), mass (kg), moment of inertia (kg·m²).
  std::vector<double> radius, mass, inertia;
  std::vector<double> volume;           ///< volume the particle stands for (m³): weights the damage index
  std::vector<std::uint8_t> fixedDofs;  ///< bit set of FixedDof

  std::size_t size() const { return x.size(); }

  /// Appends a particle at rest with identity orientation; mass and inertia are set later.
  std::size_t add(double px, double py, double pz, double r);

  /// Keeps only the particles with keep[k] != 0, in order; returns old index -> new index (-1 if removed).
  std::vector<std::int32_t> compact(const std::vector<std::uint8_t>& keep);

  /// The particles with keep[k] != 0, in order, each of their arrays copied (an array still empty
  /// stays empty); this store is unchanged. A sub-domain's particles, cut without a copy of the
  /// whole sample (distributed/subdomain.hpp).
  ParticleStore subset(const std::vector<std::uint8_t>& keep) const;

  /// Grows or shrinks every per-particle array to n (the arrays still empty stay empty); new
  /// particles are zero, with identity orientation. For a sub-domain's ghosts by distance, which
  /// come and go after the particles its bonds know (distributed/contact_halo.hpp).
  void resize(std::size_t n);

  /// Renumbers the particles: new particle k is old particle order[k] (a permutation of 0..size-1).
  /// Only while a sample is built (samples/spatial_order.hpp). Returns old index -> new index.
  std::vector<std::int32_t> permute(const std::vector<std::size_t>& order);

  /// Sets mass and inertia from a material density (kg/m³) and each particle's volume
  /// (sphere 4/3 π R³; in 2D a disk π R² × thickness), and that volume. Inertia: 2/5 m R² (sphere),
  /// 1/2 m R² (disk).
  void setMassFromDensity(double elementDensity, double thickness2d);

  /// The arrays a step changes (kinematics, loads); the constant ones are the set-up's.
  void exchangeState(StateArchive& archive);

  /// Calls f on every per-particle array of s (all but dimension), a store or a const store: the
  /// one list that compact, permute, subset and a sub-domain's transfer share.
  template <class Store, class F>
  static void forEachArrayOf(Store& s, F&& f) {
    for (auto* v : {&s.x, &s.y, &s.z, &s.vx, &s.vy, &s.vz, &s.fx, &s.fy, &s.fz, &s.qw, &s.qx, &s.qy, &s.qz, &s.wx,
                    &s.wy, &s.wz, &s.tx, &s.ty, &s.tz, &s.radius, &s.mass, &s.inertia, &s.volume})
      f(*v);
    f(s.fixedDofs);
  }

private:
  template <class F>
  void forEachArray(F&& f) {
    forEachArrayOf(*this, f);
  }
};

}  // namespace rupture
