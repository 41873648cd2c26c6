#pragma once
// A job as an RO-Crate (RO-Crate 1.1, https://w3id.org/ro/crate/1.1) following the Workflow Run
// Crate profile 0.5 (https://w3id.org/ro/wfrun/workflow/0.5; docs/provenance.md): one ZIP that
// lets a published figure be traced to what made it, read by any RO-Crate tool.
//
//   ro-crate-metadata.json   the JSON-LD description below
//   request.json             the job's request as accepted: the "workflow" (ComputationalWorkflow,
//                            the crate's mainEntity), POSTable again to /processes/{scenario}/execution
//   runs/run-K.json          each run's full spec (the object of its action)
//   runs/run-K.h5            each successful run's result, its own /provenance inside
//   summary.json, summary.csv  the job's summary table, as GET /jobs/{id}/summary gives it
//
// The metadata describes the job's execution as a CreateAction whose instrument is request.json,
// and every run as a CreateAction whose instrument is Rupture itself (a SoftwareApplication with the
// build the job was submitted to: version, commit, compiler, flags), object its spec and result its
// file, with start and end times and status. Each listed file has its contentSize in bytes.
#include <filesystem>
#include <memory>
#include <vector>

#include "jobs/job_store.hpp"
#include "views/zip_archive.hpp"

namespace rupture::server {

/// The crate of a finished job (its runs as the store lists them; result paths relative to
/// `resultsDir`). Throws std::length_error when it would reach 4 GiB (zip_archive.hpp).
std::shared_ptr<ZipArchive> jobCrate(const JobRecord& job, const std::vector<RunRecord>& runs,
                                     const std::filesystem::path& resultsDir);

}  // namespace rupture::server
