#pragma once
// The wall time a run will take, estimated before it is queued (the dry run of a submission, the
// form's preview): its estimated elements (or particles) times its estimated time steps times the
// seconds one such element-step costs in its scenario (per element where the scenario estimates no
// steps), measured with the built binary on each scenario's example at one thread (docs/server.md,
// "Preview and cost", gives the figures and how far off they can be).
#include <optional>
#include <string>

#include "rupture/run.hpp"

namespace rupture::server {

/// One scenario's measured cost.
struct CostModel {
  double secondsPerElementStep = 0;  ///< s per estimated element (or particle) per estimated step, one thread
  double secondsPerElement = 0;      ///< s per element, for a scenario whose estimate counts no steps
  const char* basis = "";            ///< what was measured, for the answer that quotes it
  const char* uncertainty = "";      ///< how far an estimate can be off, and why
};

/// The scenario's cost model, or nullptr for one without (validation: its runs are whole cases).
const CostModel* costModelFor(const std::string& scenario);

/// Seconds one run is expected to take on `threads` OpenMP threads in each of its `estimate.ranks`
/// MPI ranks (the measured cost divided by threads × ranks: ideal scaling, so an underestimate
/// where threads or ranks do not pay; two ranks step 1.5–1.9× one, docs/distributed.md); nullopt
/// when the scenario has no cost model or the estimate gives no elements or steps.
std::optional<double> estimatedRunSeconds(const std::string& scenario, const rupture::RunEstimate& estimate,
                                          int threads);

}  // namespace rupture::server
