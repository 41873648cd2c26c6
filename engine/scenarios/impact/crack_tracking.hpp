#pragma once
// Crack observables of the impact scenario, from the damage index φ of each particle (cracked:
// φ > threshold).
//   tip: the cracked particle farthest from the crack origin (the end of the first notch, else the
//        projectile's or the first loaded region's initial centre) among those connected to the
//        origin through cracked particles (linked when closer than 2.5 spacings, starting from
//        those within 3 spacings of the origin), so that cracks nucleating elsewhere (edges,
//        reflected waves) do not make the tip jump; its distance is kept as a running maximum.
//   speed: the tip distance's slope over the last `window` output rows (a smoothing window).
//   branches: cracked particles are cut into annuli (shells in 3D) around the origin, 4 spacings
//        wide; in each annulus past 6 spacings the cracked particles are clustered (linked when
//        closer than 2.5 spacings, clusters of at least 3); the branch count is the largest number
//        of clusters in one annulus: 1 for a single crack, 2 once it has branched.
#include <array>
#include <cstddef>
#include <vector>

#include "core/particle_store.hpp"

namespace rupture {

struct CrackTip {
  double x = 0, y = 0, z = 0;
  double distance = 0;  ///< from the origin (m), running maximum
  bool found = false;
};

class CrackTracker {
public:
  CrackTracker(std::array<double, 3> origin, double threshold, double spacing, std::size_t window = 5)
      : m_origin(origin), m_threshold(threshold), m_spacing(spacing), m_window(window) {}

  /// Updates the tip from the current damage and positions at time t; returns the smoothed speed (m/s).
  double observe(double t, const ParticleStore& p, const std::vector<double>& damage);
  const CrackTip& tip() const { return m_tip; }
  double maxSpeed() const { return m_maxSpeed; }

private:
  std::array<double, 3> m_origin;
  double m_threshold;
  double m_spacing;
  std::size_t m_window;
  CrackTip m_tip;
  std::vector<double> m_times, m_distances;
  double m_maxSpeed = 0;
};

/// Number of crack branches (see above); `spacing` is the particle spacing (m).
int countCrackBranches(const ParticleStore& p, const std::vector<double>& damage, double threshold,
                       std::array<double, 3> origin, double spacing);

}  // namespace rupture
