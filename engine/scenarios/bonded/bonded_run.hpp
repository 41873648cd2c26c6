#pragma once
// What every bonded scenario's run shares: its start (the sample built, through the sample cache
// when asked, with cancel honoured) and the bookkeeping scalars of its summary.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "rupture/run.hpp"
#include "samples/sample_builder.hpp"
#include "scenarios/bonded/sample_cache.hpp"

namespace rupture {

/// The start every bonded run shares: progress 0, the stage "building the sample", and the sample
/// built into `system` (through the cache in `directory` when one is given, its use told in `use`).
/// nullopt when the run was cancelled while building.
std::optional<SampleReport> buildRunSample(const SampleSpec& sample, const MaterialSpec& material, BondedSystem& system,
                                           RunControl& control, const std::string& directory = {},
                                           SampleCacheUse* use = nullptr);

/// The scalars every bonded run's summary reports about its time stepping and its sample:
/// final_time, steps, time_step, critical_time_step (s or counts), elements and bonds.
nlohmann::json bondedRunScalars(const BondedSystem& system, double timeStep, double criticalTimeStep,
                                const SampleReport& report);

}  // namespace rupture
