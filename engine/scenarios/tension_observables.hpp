#pragma once
// What the main dynamic-tension run watches at every step (O(1) per step): the peak of the mean
// boundary stress σ̄ (seed eq. 4) with the two face stresses at that step, the largest stress of
// each face, the first broken bond, the number of broken bonds; the stop rule and the progress
// estimate built on them.
#include <cstddef>
#include <limits>

#include <nlohmann/json.hpp>

#include "scenarios/tension_loading.hpp"

namespace rupture {

class TensionObservables {
public:
  explicit TensionObservables(std::size_t initialBonds) : m_initialBonds(initialBonds) {}

  /// Call after every step with the state at its end.
  void observe(double time, double strain, const FaceStresses& stress, std::size_t brokenThisStep);

  /// Stop rule: bonds have started to break and σ̄ fell below stopFraction × its peak.
  bool postPeakDrop(double stopFraction) const;

  /// Fraction done in [0, 1]: before the first break, ½ × the time over the estimated time of the
  /// first break (the worst bond's stress over its strength grows about linearly with ε, which
  /// extrapolates the onset strain; `ramp` converts it to a time); after it, ½ + ½ × the drop of σ̄
  /// towards the stop level; at least ε / maxStrain.
  double progress(double time, const VelocityRamp& ramp, double gaugeLength, double maxStrain, double stopFraction,
                  double worstBondStressRatio) const;

  std::size_t broken() const { return m_broken; }
  double brokenFraction() const {
    return m_initialBonds ? static_cast<double>(m_broken) / static_cast<double>(m_initialBonds) : 0.0;
  }
  double onsetTime() const { return m_onsetTime; }

  /// peak_stress, strain_at_peak, time_at_peak, stress_{xmin,xmax}_at_peak, max_stress_{xmin,xmax},
  /// equilibrium_ratio, crack_onset_{strain,time}, broken_bond_fraction, broken_bonds (null for
  /// values that do not exist, e.g. no broken bond).
  nlohmann::json summary() const;

private:
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::size_t m_initialBonds;
  std::size_t m_broken = 0;
  double m_strain = 0;
  FaceStresses m_last;
  double m_peak = -std::numeric_limits<double>::infinity(), m_strainAtPeak = kNaN, m_timeAtPeak = kNaN;
  double m_xminAtPeak = kNaN, m_xmaxAtPeak = kNaN, m_maxXmin = 0, m_maxXmax = 0;
  double m_onsetStrain = kNaN, m_onsetTime = kNaN;
};

}  // namespace rupture
