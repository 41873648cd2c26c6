#pragma once
// The relaxation behind every quasi-static tension test (calibration.hpp): the sample on the affine
// field at strain ε, its X faces held in x, failure and contact off, relaxed by Cundall-damped
// dynamics until E and ν change by less than the tolerance over a check interval. A class, not a
// loop in a function, so that a checkpoint can hold it mid-way (test_journal.hpp): its state is
// the system and where the loop stands; everything else is set up again from the sample.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bonded/bonded_system.hpp"
#include "bonded/sample_spec.hpp"
#include "calibration/calibration.hpp"
#include "rupture/state_archive.hpp"

namespace rupture {

class ElasticRelaxation {
public:
  /// Sets the test up on a copy of `sample` (throws CalibrationError for a sample it cannot test).
  ElasticRelaxation(const BondedSystem& sample, const SampleSpec& spec, const CalibrationOptions& options);

  /// Relaxes until converged, the step budget, cancel or a stop of the run's checkpoints
  /// (options.journal); returns E and ν as they stand (converged only in the first case).
  ElasticProperties run();
  /// The run ended on cancel or a stop, not on convergence or the budget.
  bool stopped() const { return m_stopped; }

  /// The relaxed (or relaxing) system: faces held in x, failure and contact off.
  BondedSystem& system() { return m_system; }
  const BondedSystem& system() const { return m_system; }
  /// The system and the loop's position (the test's part of a checkpoint).
  void exchangeState(StateArchive& archive);

private:
  ElasticProperties measure() const;

  const CalibrationOptions& m_options;
  BondedSystem m_system;
  TensionFaces m_faces;
  std::vector<double> m_x0, m_y0, m_z0;
  double m_section = 0, m_dt = 0;
  std::size_t m_interval = 0;
  // Where the loop stands.
  std::size_t m_inInterval = 0;     ///< steps taken in the current check interval
  ElasticProperties m_previous;     ///< the last check's values
  double m_firstChange = 0;         ///< the change at the first check, for the progress estimate
  bool m_stopped = false;
};

}  // namespace rupture
