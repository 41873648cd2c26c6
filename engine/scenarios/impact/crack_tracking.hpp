#pragma once
// Crack observables of the impact scenario, from the damage index φ of each particle (cracked:
// φ > threshold).
//   tip: the cracked particle farthest from the crack origin (the end of the first notch, else the
//        projectile's or the first loaded region's initial centre) among those connected to the
//        origin through cracked particles (linked when closer than 2.5 spacings, starting from
//        those within 3 spacings of the origin), so that cracks nucleating elsewhere (edges,
//        reflected waves) do not make the tip jump; its distance is kept as a running maximum.
//   speed: the slope of the propagated length over the last `window` output rows (a smoothing
//        window). The propagated length is the tip distance less its jumps: when a zone that
//        cracked apart from the crack (ahead of it, from a reflected wave) joins it, the tip moves
//        at once by that zone's extent, faster than any crack can run (`maxSpeed`, the material's
//        bar wave speed sqrt(E/rho) twice over, plus two spacings per output row); such a gain is a
//        jump, reported as an event (jump()) and kept out of the speed, so that crack_speed_max is
//        the speed of a crack and never that of two zones joining.
//   angle: the direction of the tip from the origin, measured from the first notch's direction
//        (end − start): in 2D signed, counter-clockwise positive in the x–y plane, in (−π, π]; in 3D
//        the angle between the two directions, in [0, π]. A notch loaded in shear (Kalthoff and
//        Winkler's plate) kinks by about 70° (Kalthoff 2000); one opened in tension runs straight on (0).
//   branches: cracked particles are cut into annuli (shells in 3D) around the origin, 4 spacings
//        wide; in each annulus past 6 spacings the cracked particles are clustered (linked when
//        closer than 2.5 spacings, clusters of at least 3); the branch count is the largest number
//        of clusters in one annulus: 1 for a single crack, 2 once it has branched.
#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "core/particle_store.hpp"
#include "rupture/state_archive.hpp"

namespace rupture {

struct CrackTip {
  double x = 0, y = 0, z = 0;
  double distance = 0;  ///< from the origin (m), running maximum
  bool found = false;
};

class CrackTracker {
public:
  CrackTracker(std::array<double, 3> origin, double threshold, double spacing, std::size_t window = 5,
               double maxSpeed = std::numeric_limits<double>::infinity())
      : m_origin(origin), m_threshold(threshold), m_spacing(spacing), m_window(window), m_jumpSpeed(maxSpeed) {}

  /// Updates the tip from the current damage and positions at time t; returns the smoothed speed (m/s).
  double observe(double t, const ParticleStore& p, const std::vector<double>& damage);
  const CrackTip& tip() const { return m_tip; }
  double maxSpeed() const { return m_maxSpeed; }
  /// The length the tip gained at once at the last observation by joining a zone that cracked
  /// apart from it (m; 0 when it did not jump).
  double jump() const { return m_jump; }
  /// How many times the tip jumped, and by how much in all (m).
  int jumps() const { return m_jumps; }
  double jumpedLength() const { return m_jumped; }

  /// The tip and its history (docs/checkpoints.md).
  void exchangeState(StateArchive& archive) {
    StateGroup group(archive, "crack_tracker");
    archive.record("tip", m_tip);
    archive.array("times", m_times), archive.array("distances", m_distances);
    archive.value("max_speed", m_maxSpeed);
    archive.value("jump", m_jump), archive.value("jumped", m_jumped), archive.value("last_distance", m_lastDistance);
    archive.value("last_found", m_lastFound);
    archive.value("jumps", m_jumps);
  }

private:
  std::array<double, 3> m_origin;
  double m_threshold;
  double m_spacing;
  std::size_t m_window;
  double m_jumpSpeed;
  CrackTip m_tip;
  std::vector<double> m_times, m_distances;  ///< the propagated length (jumps taken off)
  double m_maxSpeed = 0;
  double m_jump = 0, m_jumped = 0, m_lastDistance = 0;
  bool m_lastFound = false;
  int m_jumps = 0;
};

/// The crack's angle (rad, see above): the direction of `tip` from the notch's end `to`, measured
/// from the notch's direction `from` → `to`; nullopt when no crack was found or the notch has no length.
std::optional<double> crackAngle(const CrackTip& tip, std::array<double, 3> from, std::array<double, 3> to,
                                 int dimension);

/// Number of crack branches (see above); `spacing` is the particle spacing (m).
int countCrackBranches(const ParticleStore& p, const std::vector<double>& damage, double threshold,
                       std::array<double, 3> origin, double spacing);

}  // namespace rupture
