#pragma once
// What a checkpoint of a workload's state costs (docs/checkpoints.md): its size and the wall time
// of writing it, as a run writes it (io::Hdf5StateArchive, uncompressed, synced to the disk), into a
// temporary file that is then removed. A run's checkpoint also holds a copy of its result file so far (its snapshots):
// the TANK workload, which runs the scenario, reports that whole cost.
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "io/hdf5_file.hpp"
#include "io/hdf5_state_archive.hpp"

namespace rupture::bench {

inline nlohmann::json checkpointCost(const std::function<void(StateArchive&)>& state) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("rupture-bench-checkpoint-" + std::to_string(::getpid()) + ".h5");
  const auto start = std::chrono::steady_clock::now();
  {
    io::Hdf5File file = io::Hdf5File::create(path.string());
    io::Hdf5StateArchive archive(file, "/checkpoint/state", io::Hdf5StateArchive::Mode::Save);
    state(archive);
    file.close();
  }
  // On the disk, as a checkpoint is before its rename (io/checkpoint_file.cpp).
  if (const int fd = ::open(path.c_str(), O_RDONLY); fd >= 0) {
    [[maybe_unused]] const int rc = ::fsync(fd);
    ::close(fd);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto bytes = std::filesystem::file_size(path);
  std::filesystem::remove(path);
  return {{"checkpoint_bytes", bytes}, {"checkpoint_seconds", seconds},
          {"checkpoint_overhead_at_300_s", seconds / 300.0}};
}

}  // namespace rupture::bench
