#pragma once
// The JSON documents that describe a job, a run and a process (OGC API - Processes statusInfo and
// process summary, with Rupture's sweep members).
#include <vector>

#include "jobs/job_store.hpp"
#include "rupture/run.hpp"

namespace rupture::server {

/// A fraction in [0, 1] as a whole percentage, rounded down (100 only when done).
int percent(double fraction);

Json runDocument(const JobRecord& job, const RunRecord& run);

/// statusInfo of a job; with `runs`, each run's document too.
Json statusInfo(const JobRecord& job, const std::vector<RunRecord>* runs);

/// This server's build and host (io/provenance.hpp): rupture_version, git_commit, compiler,
/// compile_flags, build_type, host_processor. GET /health shows it; a job records it when submitted.
Json buildDocument();

Json processSummary(const rupture::ScenarioInfo& info);

}  // namespace rupture::server
