#pragma once
// What every run's memory estimate starts from (RunEstimate::memoryBytes, rupture/run.hpp).

namespace rupture::io {

/// Peak resident memory of a run before its particles count: the program, its libraries, HDF5's
/// caches and the result file's buffers. Measured 20-22 MiB for the smallest examples (2D and 3D
/// dynamic tension of about 1,500 elements, 2026-11-27), rounded up.
inline constexpr double kRunBaseBytes = 32.0 * 1024 * 1024;

}  // namespace rupture::io
