#pragma once
// Progress on stderr for the long commands (run, calibrate): a redrawn bar with an ETA on a
// terminal, a plain line every `lineInterval` seconds otherwise (logs, Slurm output files), and
// stage messages that never collide with the bar.
#include <chrono>
#include <functional>
#include <mutex>
#include <string>

#include "rupture/progress.hpp"

namespace rupture::cli {

/// h:mm:ss or m:ss; "unknown" for a negative (unknown) duration, "--" for an absurd one.
std::string clockText(double seconds);

class ProgressView {
public:
  /// `prefix` starts every plain line ("rupture run"); `terminal`: stderr is a terminal;
  /// `lineInterval`: seconds between plain lines off a terminal.
  ProgressView(std::string prefix, bool terminal, double lineInterval = 10.0);

  /// What a plain line says after its prefix, given the fraction done and the ETA (s, negative:
  /// unknown); without it, the percentage with the elapsed time and the ETA.
  using LineText = std::function<std::string(double fraction, double etaSeconds)>;
  void setLineText(LineText text) { m_lineText = std::move(text); }

  /// A stage message on its own line (clears a bar in progress first).
  void message(const std::string& text);
  /// The fraction done in [0, 1]; `label`, when given, names what the fraction is of. `force`
  /// prints a plain line now even if one was printed less than 10 s ago. `withEta` false: the
  /// fraction is no measure of time left (a relaxation of unknown length), so no ETA is shown.
  void update(double fraction, bool force = false, const std::string& label = "", bool withEta = true);
  /// Ends a bar's line.
  void close();

private:
  std::string m_prefix;
  bool m_terminal;
  double m_lineInterval;
  LineText m_lineText;
  std::chrono::steady_clock::time_point m_start;
  std::mutex m_mutex;
  bool m_barShown = false;
  double m_lastLine = 0;
  RemainingTime m_remaining;
};

}  // namespace rupture::cli
