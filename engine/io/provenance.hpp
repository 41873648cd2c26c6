#pragma once
// What made a result file, on its "/provenance" group (docs/provenance.md): the build (version, git
// commit, compiler, flags, build type), the host processor and the OpenMP threads, when the run
// started and finished (UTC), the SHA-256 of its resolved spec and the random seeds in it. A
// published figure can so be traced to the code, the machine and the input that made it.
//
// ResultFile writes it: the build and host when the file is created, the spec's digest and seeds
// with the spec, the finish time when it is closed. A resumed run keeps the first attempt's start
// and adds its finish (its attempts are in checkpoint_resumes and resumed_from_steps on "/").
#include <string>

#include <nlohmann/json.hpp>

#include "io/hdf5_file.hpp"

namespace rupture::io {

struct BuildInfo {
  std::string version;    ///< the project's version
  std::string commit;     ///< git commit the build was made from ("-dirty" with uncommitted changes; "unknown" outside git)
  std::string compiler;   ///< e.g. "GNU 12.2.0"
  std::string flags;      ///< C++ flags of the build type and the project's compile options
  std::string buildType;  ///< CMake build type
};
/// This build's.
const BuildInfo& buildInfo();

/// The host's processor as the kernel names it (/proc/cpuinfo "model name"), else the machine type.
std::string hostProcessor();

/// Now, as ISO 8601 UTC to the second ("2026-11-28T12:00:57Z").
std::string utcNow();

/// The provenance of a run as JSON: the build, host processor, threads and start time.
nlohmann::json startProvenance(int threads);
/// Every seed of a resolved spec: {"sample.seed": 7, ...} (keys named "seed" or ending in "_seed").
nlohmann::json specSeeds(const nlohmann::json& resolved);

/// Writes the group's start, spec and finish attributes (see above).
void writeStartProvenance(Hdf5File& file);
void writeSpecProvenance(Hdf5File& file, const nlohmann::json& resolved);
void writeFinishProvenance(Hdf5File& file);

}  // namespace rupture::io
