#include "scenarios/tension_observables.hpp"

#include <algorithm>
#include <cmath>

namespace rupture {

namespace {
nlohmann::json nullIfNaN(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
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
  }
  if (stress.mean > m_peak) {
    m_peak = stress.mean;
    m_strainAtPeak = strain;
    m_timeAtPeak = time;
    m_xminAtPeak = stress.xmin;
    m_xmaxAtPeak = stress.xmax;
  }
  m_maxXmin = std::max(m_maxXmin, stress.xmin);
  m_maxXmax = std::max(m_maxXmax, stress.xmax);
}

bool TensionObservables::postPeakDrop(double stopFraction) const {
  return m_broken > 0 && m_peak > 0 && m_last.mean < stopFraction * m_peak;
}

double TensionObservables::progress(double time, const VelocityRamp& ramp, double gaugeLength, double maxStrain,
                                    double stopFraction, double worstBondStressRatio) const {
  double p = 0;
  if (m_broken == 0) {
    if (worstBondStressRatio > 1e-3) {
      const double onset = ramp.timeToReach(m_strain / worstBondStressRatio * gaugeLength);
      p = onset > 0 ? 0.5 * std::min(1.0, time / onset) : 0.0;
    }
  } else {
    p = 0.5 + 0.5 * std::clamp((m_peak - m_last.mean) / (m_peak * (1.0 - stopFraction)), 0.0, 1.0);
  }
  return std::clamp(std::max(p, m_strain / maxStrain), 0.0, 1.0);
}

nlohmann::json TensionObservables::summary() const {
  const bool peakFound = std::isfinite(m_peak);
  const double ratio = peakFound && m_peak != 0 ? std::abs(m_xminAtPeak - m_xmaxAtPeak) / std::abs(m_peak) : kNaN;
  return {{"peak_stress", nullIfNaN(peakFound ? m_peak : kNaN)},
          {"strain_at_peak", nullIfNaN(m_strainAtPeak)},
          {"time_at_peak", nullIfNaN(m_timeAtPeak)},
          {"stress_xmin_at_peak", nullIfNaN(m_xminAtPeak)},
          {"stress_xmax_at_peak", nullIfNaN(m_xmaxAtPeak)},
          {"max_stress_xmin", m_maxXmin},
          {"max_stress_xmax", m_maxXmax},
          {"equilibrium_ratio", nullIfNaN(ratio)},
          {"crack_onset_strain", nullIfNaN(m_onsetStrain)},
          {"crack_onset_time", nullIfNaN(m_onsetTime)},
          {"broken_bond_fraction", brokenFraction()},
          {"broken_bonds", static_cast<std::int64_t>(m_broken)}};
}

}  // namespace rupture
