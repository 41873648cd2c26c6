#pragma once
// What the main dynamic-tension run watches at every step (O(1) per step, amortised): the peak of
// the mean boundary stress σ̄ (seed eq. 4) with the two face stresses at that step, the largest
// stress of each face, the first and the last broken bond, the number of broken bonds, the sums
// behind the equilibrium ratio of the loading branch, and the separation of the two faces; the
// stop rules and the progress estimate built on them.
//
// Equilibrium ratio of the loading branch (the seed's reading of its Fig. 2: the two face curves
// overlap up to the peak):
//   R_eq = Σ_s |σ_Xmax − σ_Xmin| / Σ_s σ̄,  over the steps s with ¼ ε_peak ≤ ε_s ≤ ε_peak
// i.e. the mean face-stress difference over the mean stress on 25–100 % of the strain at the peak
// (a ratio of means: σ̄ is small at the start of the window and a mean of ratios would weigh those
// steps most). The sums are kept as running totals with checkpoints thinned to at most 4096, so
// the window starts within 1/2048 of the run's steps of ¼ ε_peak.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <nlohmann/json.hpp>

#include "rupture/state_archive.hpp"
#include "scenarios/dynamic_tension/tension_loading.hpp"

namespace rupture {

class TensionObservables {
public:
  explicit TensionObservables(std::size_t initialBonds) : m_initialBonds(initialBonds) {}

  /// Call after every step with the state at its end.
  void observe(double time, double strain, const FaceStresses& stress, std::size_t brokenThisStep);

  /// Stop rule: bonds have started to break and σ̄ fell below stopFraction × its peak.
  bool postPeakDrop(double stopFraction) const;

  /// Records that no path of intact bonds joins the faces any more (first call counts).
  void markSeparated(double time, double strain);
  bool separated() const { return m_separated; }
  /// Stop rule: separated, and no bond broke during the last `quietTime` (s).
  bool settledAfterSeparation(double time, double quietTime) const {
    return m_separated && time - std::max(m_separationTime, m_lastBreakTime) >= quietTime;
  }
  /// Stop rule for a sample broken but still joined by a ligament that carries almost nothing:
  /// bonds have broken, none during the last `quietTime`, the peak is that long past, and σ̄
  /// averaged over about `quietTime` (exponential moving average, set by setAveragingTime) is
  /// below `fraction` × peak.
  bool unloadedAndQuiet(double time, double quietTime, double fraction) const {
    return m_broken > 0 && m_peak > 0 && time - m_lastBreakTime >= quietTime && time - m_timeAtPeak >= quietTime &&
           std::abs(m_averageMean) < fraction * m_peak;
  }
  /// Time constant of the moving average of σ̄ used by unloadedAndQuiet (s); 0: σ̄ itself.
  void setAveragingTime(double tau) { m_averagingTime = tau; }

  std::size_t broken() const { return m_broken; }
  double strainAtPeak() const { return m_strainAtPeak; }
  double brokenFraction() const {
    return m_initialBonds ? static_cast<double>(m_broken) / static_cast<double>(m_initialBonds) : 0.0;
  }
  double onsetTime() const { return m_onsetTime; }
  double lastBreakTime() const { return m_lastBreakTime; }
  double separationTime() const { return m_separationTime; }

  /// R_eq above (NaN without a positive peak).
  double loadingEquilibriumRatio() const;

  /// peak_stress, strain_at_peak, time_at_peak, stress_{xmin,xmax}_at_peak, max_stress_{xmin,xmax},
  /// equilibrium_ratio (R_eq), equilibrium_ratio_at_peak, crack_onset_{strain,time},
  /// broken_bond_fraction, broken_bonds, separated, separation_{strain,time} (null for values that
  /// do not exist, e.g. no broken bond).
  nlohmann::json summary() const;

  /// Every running value (docs/checkpoints.md).
  void exchangeState(StateArchive& archive);

private:
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  struct Checkpoint {
    double strain, sumDifference, sumMean;
  };
  std::size_t m_initialBonds;
  std::size_t m_broken = 0;
  double m_strain = 0;
  FaceStresses m_last;
  double m_peak = -std::numeric_limits<double>::infinity(), m_strainAtPeak = kNaN, m_timeAtPeak = kNaN;
  double m_xminAtPeak = kNaN, m_xmaxAtPeak = kNaN, m_maxXmin = 0, m_maxXmax = 0;
  double m_onsetStrain = kNaN, m_onsetTime = kNaN, m_lastBreakTime = kNaN;
  bool m_separated = false;
  double m_separationStrain = kNaN, m_separationTime = kNaN;
  double m_averagingTime = 0, m_averageMean = 0, m_lastTime = 0;
  // Running sums of |σ_Xmax − σ_Xmin| and σ̄ over the steps, their values at the peak step, and
  // checkpoints every m_stride steps.
  double m_sumDifference = 0, m_sumMean = 0, m_sumDifferenceAtPeak = 0, m_sumMeanAtPeak = 0;
  std::vector<Checkpoint> m_checkpoints;
  std::uint64_t m_steps = 0, m_stride = 1;
};

}  // namespace rupture
