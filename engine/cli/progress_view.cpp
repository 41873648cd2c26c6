#include "cli/progress_view.hpp"

#include <cstdio>
#include <iostream>

#include "rupture/progress.hpp"

namespace rupture::cli {

std::string clockText(double seconds) {
  if (seconds < 0) return "unknown";
  if (!(seconds >= 0) || seconds > 1e7) return "--";
  const long s = static_cast<long>(seconds + 0.5);
  char buffer[32];
  if (s >= 3600) std::snprintf(buffer, sizeof buffer, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else std::snprintf(buffer, sizeof buffer, "%ld:%02ld", s / 60, s % 60);
  return buffer;
}

ProgressView::ProgressView(std::string prefix, bool terminal, double lineInterval)
    : m_prefix(std::move(prefix)), m_terminal(terminal), m_lineInterval(lineInterval),
      m_start(std::chrono::steady_clock::now()) {}

void ProgressView::message(const std::string& text) {
  std::lock_guard lock(m_mutex);
  if (m_terminal && m_barShown) std::cerr << "\r\033[K";
  std::cerr << m_prefix << ": " << text << "\n";
  m_barShown = false;
}

void ProgressView::update(double fraction, bool force, const std::string& label, bool withEta) {
  std::lock_guard lock(m_mutex);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
  m_remaining.observe(elapsed, fraction);
  const double eta = m_remaining.at(elapsed);
  const std::string what = label.empty() ? "" : label + " ";
  const std::string etaText = withEta ? "ETA " + clockText(eta) : "";
  char line[240];
  if (m_terminal) {
    constexpr int width = 30;
    const int filled = static_cast<int>(fraction * width + 0.5);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.append(static_cast<std::size_t>(width - filled), '.');
    std::snprintf(line, sizeof line, "\r\033[K%s[%s] %5.1f %%  elapsed %s  %s", what.c_str(), bar.c_str(),
                  100.0 * fraction, clockText(elapsed).c_str(), etaText.c_str());
    std::cerr << line << std::flush;
    m_barShown = true;
  } else if (force || elapsed - m_lastLine >= m_lineInterval) {
    m_lastLine = elapsed;
    if (m_lineText) {
      std::cerr << m_prefix << ": " << m_lineText(fraction, withEta ? eta : -1.0) << "\n" << std::flush;
      return;
    }
    std::snprintf(line, sizeof line, "%s: %s%.0f %% (elapsed %s%s%s)\n", m_prefix.c_str(), what.c_str(),
                  100.0 * fraction, clockText(elapsed).c_str(), withEta ? ", " : "", etaText.c_str());
    std::cerr << line << std::flush;
  }
}

void ProgressView::close() {
  std::lock_guard lock(m_mutex);
  if (m_terminal && m_barShown) std::cerr << "\n";
  m_barShown = false;
}

}  // namespace rupture::cli
