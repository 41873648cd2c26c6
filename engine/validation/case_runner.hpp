#pragma once
// Runs a validation case's specs, one after the other, as any run is made (rupture::runSpec), and
// keeps what its comparison reads: each member's summary and the series its quantities and figure
// need. The members' files are written under a work directory and removed once read.
#include <optional>
#include <string>

#include "rupture/run.hpp"
#include "validation/validation_case.hpp"

namespace rupture::validation {

/// The data of every run of `c` at `level`, or nullopt when `control` was cancelled. `control`'s
/// cancel reaches the run under way within its own check interval; its progress counts the runs
/// done plus the fraction of the one under way. Throws what a run throws.
std::optional<CaseRunData> runCase(const ValidationCase& c, const std::string& level, const std::string& workDirectory,
                                   RunControl& control, int threads);

}  // namespace rupture::validation
