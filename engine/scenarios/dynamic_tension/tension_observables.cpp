#include "scenarios/dynamic_tension/tension_observables.hpp"
#include "scenarios/run_support.hpp"

#include <algorithm>
#include <cmath>

namespace rupture {

namespace {
constexpr std::size_t kMaxCheckpoints = 4096;
}  // namespace

void TensionObservables::observe(double time, double strain, const FaceStresses& stress, std::size_t brokenThisStep) {
  m_strain = strain;
  m_last = stress;
  if (brokenThisStep > 0) {
    if (m_broken == 0) {
      m_onsetStrain = strain;
      m_onsetTime = time;
    }
    m_broken += brokenThisStep;
    m_lastBreakTime = time;
  }
  const double dt = time - m_lastTime;
  m_lastTime = time;
  m_averageMean = m_averagingTime > 0 ? m_averageMean + std::min(1.0, dt / m_averagingTime) * (stress.mean - m_averageMean)
                                      : stress.mean;
  m_sumDifference += std::abs(stress.xmax - stress.xmin);
  m_sumMean += stress.mean;
  if (stress.mean > m_peak) {
    m_peak = stress.mean;
    m_strainAtPeak = strain;
    m_timeAtPeak = time;
    m_xminAtPeak = stress.xmin;
    m_xmaxAtPeak = stress.xmax;
    m_sumDifferenceAtPeak = m_sumDifference;
    m_sumMeanAtPeak = m_sumMean;
  }
  m_maxXmin = std::max(m_maxXmin, stress.xmin);
  m_maxXmax = std::max(m_maxXmax, stress.xmax);
  if (++m_steps % m_stride == 0) {
    if (m_checkpoints.size() == kMaxCheckpoints) {  // keep every other one, twice the stride
      for (std::size_t k = 0; k < kMaxCheckpoints / 2; ++k) m_checkpoints[k] = m_checkpoints[2 * k + 1];
      m_checkpoints.resize(kMaxCheckpoints / 2);
      m_stride *= 2;
    }
    if (m_steps % m_stride == 0) m_checkpoints.push_back({strain, m_sumDifference, m_sumMean});
  }
}

bool TensionObservables::postPeakDrop(double stopFraction) const {
  return m_broken > 0 && m_peak > 0 && m_last.mean < stopFraction * m_peak;
}

void TensionObservables::markSeparated(double time, double strain) {
  if (m_separated) return;
  m_separated = true;
  m_separationTime = time;
  m_separationStrain = strain;
}

double TensionObservables::loadingEquilibriumRatio() const {
  if (!(m_peak > 0)) return kNaN;
  // Sums before the window: the last checkpoint below ¼ ε_peak (none: the window starts at step 1).
  const double start = 0.25 * m_strainAtPeak;
  double difference = 0, mean = 0;
  for (const Checkpoint& c : m_checkpoints) {
    if (c.strain >= start) break;
    difference = c.sumDifference;
    mean = c.sumMean;
  }
  const double windowMean = m_sumMeanAtPeak - mean;
  return windowMean > 0 ? (m_sumDifferenceAtPeak - difference) / windowMean : kNaN;
}

nlohmann::json TensionObservables::summary() const {
  const bool peakFound = std::isfinite(m_peak);
  const double atPeak = peakFound && m_peak != 0 ? std::abs(m_xminAtPeak - m_xmaxAtPeak) / std::abs(m_peak) : kNaN;
  return {{"peak_stress", nullIfNaN(peakFound ? m_peak : kNaN)},
          {"strain_at_peak", nullIfNaN(m_strainAtPeak)},
          {"time_at_peak", nullIfNaN(m_timeAtPeak)},
          {"stress_xmin_at_peak", nullIfNaN(m_xminAtPeak)},
          {"stress_xmax_at_peak", nullIfNaN(m_xmaxAtPeak)},
          {"max_stress_xmin", m_maxXmin},
          {"max_stress_xmax", m_maxXmax},
          {"equilibrium_ratio", nullIfNaN(loadingEquilibriumRatio())},
          {"equilibrium_ratio_at_peak", nullIfNaN(atPeak)},
          {"crack_onset_strain", nullIfNaN(m_onsetStrain)},
          {"crack_onset_time", nullIfNaN(m_onsetTime)},
          {"broken_bond_fraction", brokenFraction()},
          {"broken_bonds", static_cast<std::int64_t>(m_broken)},
          {"separated", m_separated ? 1 : 0},
          {"separation_strain", nullIfNaN(m_separationStrain)},
          {"separation_time", nullIfNaN(m_separationTime)}};
}

void TensionObservables::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "observables");
  archive.value("broken", m_broken);
  archive.value("strain", m_strain);
  archive.record("last", m_last);
  for (auto [name, v] : {std::pair<const char*, double*>{"peak", &m_peak}, {"strain_at_peak", &m_strainAtPeak},
                         {"time_at_peak", &m_timeAtPeak}, {"xmin_at_peak", &m_xminAtPeak},
                         {"xmax_at_peak", &m_xmaxAtPeak}, {"max_xmin", &m_maxXmin}, {"max_xmax", &m_maxXmax},
                         {"onset_strain", &m_onsetStrain}, {"onset_time", &m_onsetTime},
                         {"last_break_time", &m_lastBreakTime}, {"separation_strain", &m_separationStrain},
                         {"separation_time", &m_separationTime}, {"averaging_time", &m_averagingTime},
                         {"average_mean", &m_averageMean}, {"last_time", &m_lastTime},
                         {"sum_difference", &m_sumDifference}, {"sum_mean", &m_sumMean},
                         {"sum_difference_at_peak", &m_sumDifferenceAtPeak}, {"sum_mean_at_peak", &m_sumMeanAtPeak}})
    archive.value(name, *v);
  archive.value("separated", m_separated);
  archive.records("window_marks", m_checkpoints);
  archive.value("steps", m_steps);
  archive.value("stride", m_stride);
}

}  // namespace rupture
