#pragma once
// The periodic status line of a running simulation, as LAMMPS' thermo output gives it, for a
// reader of a log (the CLI off a terminal, the server's log), and the timing breakdown at a run's
// end. One line, fields joined by " | ", each a name and a value in engineering units:
//   elapsed 12.3 s | 41 % | ETA 17.2 s | step 12000 | time 1.23 ns | strain 4.1e-4 |
//   mean stress 58.4 MPa | broken bonds 120 | 1520 steps/s | 2.43e6 particle-steps/s
// A field the run does not have (strain in a dam break, bonds in a fluid) is left out.
#include <cstdint>
#include <string>
#include <vector>

#include "rupture/run.hpp"
#include "rupture/run_status.hpp"

namespace rupture::io {

class StatusLine {
public:
  /// Every sample the watcher takes (any period): the speed of the next line counts the steps
  /// since the previous line, or since the first sample of the run stepping.
  void observe(const RunStatus& status, double wallSeconds);
  /// The line for the latest sample, `fraction` done and `etaSeconds` left (negative: unknown).
  std::string line(double fraction, double etaSeconds);

private:
  RunStatus m_status;
  double m_wall = 0;
  std::int64_t m_speedStep = -1;
  double m_speedWall = 0;
};

/// The timing breakdown at a run's end, one line per phase (its wall time and share), then a
/// total with the steps taken since `firstStep` (a resumed run's checkpoint step, else 0) and the
/// mean speed over the phase kSteppingPhase.
std::vector<std::string> timingBreakdown(const std::vector<RunPhases::Phase>& phases, const RunStatus& last,
                                         double totalSeconds, std::int64_t firstStep);

/// The breakdown of a run that has ended, from its RunControl: its phases over their sum, its last
/// status, the steps since the checkpoint it resumed from.
std::vector<std::string> timingBreakdown(const RunControl& control);

}  // namespace rupture::io
