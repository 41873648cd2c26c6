#include "io/status_line.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rupture/quantity_text.hpp"

namespace rupture::io {
namespace {

std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f %%", 100.0 * fraction);
  return text;
}

/// A rate's number as formatQuantity writes a rate (three digits, 8.13e6): not a count, which it
/// would write whole (8130000).
std::string rateNumber(double perSecond) {
  const std::string text = formatQuantity(perSecond, "1/s");
  return text.substr(0, text.find(' '));
}

/// " | steps/s | particle-steps/s" for `steps` over `seconds` (nothing when not measurable).
std::string speedFields(double steps, double seconds, double particles) {
  if (!(seconds > 0) || !(steps >= 0)) return "";
  const double rate = steps / seconds;
  std::string out = " | " + rateNumber(rate) + " steps/s";
  if (particles > 0) out += " | " + rateNumber(rate * particles) + " particle-steps/s";
  return out;
}

}  // namespace

void StatusLine::observe(const RunStatus& status, double wallSeconds) {
  m_status = status;
  m_wall = wallSeconds;
  if (m_speedStep < 0 && status.step >= 0) {
    m_speedStep = status.step;
    m_speedWall = wallSeconds;
  }
}

std::string StatusLine::line(double fraction, double etaSeconds) {
  const RunStatus& s = m_status;
  std::string out = "elapsed " + formatQuantity(m_wall, "s") + " | " + percent(fraction) + " | ETA " +
                    (etaSeconds >= 0 ? formatQuantity(etaSeconds, "s") : std::string("unknown"));
  if (s.step >= 0) out += " | step " + std::to_string(s.step);
  if (std::isfinite(s.time)) out += " | time " + formatQuantity(s.time, "s");
  if (std::isfinite(s.strain)) out += " | strain " + formatQuantity(s.strain, "1");
  if (!s.headlineName.empty() && std::isfinite(s.headline))
    out += " | " + s.headlineName + " " + formatQuantity(s.headline, s.headlineUnit);
  if (s.brokenBonds >= 0) out += " | broken bonds " + std::to_string(s.brokenBonds);
  if (m_speedStep >= 0 && s.step >= 0) {
    out += speedFields(static_cast<double>(s.step - m_speedStep), m_wall - m_speedWall, s.particles);
    m_speedStep = s.step;
    m_speedWall = m_wall;
  }
  return out;
}

std::vector<std::string> timingBreakdown(const std::vector<RunPhases::Phase>& phases, const RunStatus& last,
                                         double totalSeconds, std::int64_t firstStep) {
  std::vector<std::string> lines;
  double stepping = 0;
  for (const RunPhases::Phase& p : phases) {
    const double share = totalSeconds > 0 ? p.seconds / totalSeconds : 0.0;
    lines.push_back("timing: " + p.name + " " + formatQuantity(std::max(p.seconds, 0.0), "s") + " (" +
                    percent(share) + ")");
    if (p.name == kSteppingPhase) stepping = std::max(p.seconds, 0.0);
  }
  std::string total = "timing: total " + formatQuantity(totalSeconds, "s");
  if (last.step >= 0) {
    const double steps = static_cast<double>(last.step - std::max<std::int64_t>(firstStep, 0));
    total += " | " + formatQuantity(steps, "1") + " steps";
    if (stepping > 0) total += speedFields(steps, stepping, last.particles);
  }
  lines.push_back(total);
  return lines;
}

std::vector<std::string> timingBreakdown(const RunControl& control) {
  const std::vector<RunPhases::Phase> phases = control.phases.totals();
  double total = 0;
  for (const RunPhases::Phase& p : phases) total += std::max(p.seconds, 0.0);
  return timingBreakdown(phases, control.status.latest(), total, control.resumedFromStep.load());
}

}  // namespace rupture::io
