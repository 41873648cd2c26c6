#pragma once
// Durable file operations for the data directory: whole-file atomic writes and renames that
// survive a crash (write to a temporary name, fsync, rename, fsync the directory).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace rupture::server {

/// Writes `content` to `path` atomically: a reader sees the old file or the new one, never a part.
void writeFileAtomic(const std::filesystem::path& path, const std::string& content);

/// Writes `content` to `path` (replacing it) and fsyncs it, without a rename: the first half of
/// writeFileAtomic, for a caller that renames it itself. A failed write leaves no file.
void writeFileSynced(const std::filesystem::path& path, const std::string& content);

/// fsyncs a file's content to the disk (throws when it cannot be opened or synced).
void syncFile(const std::filesystem::path& path);

/// fsyncs `from`, renames it to `to` and fsyncs the directory.
void renameDurable(const std::filesystem::path& from, const std::filesystem::path& to);

/// The whole file, or nullopt when it cannot be read.
std::optional<std::string> readFile(const std::filesystem::path& path);

/// Size of a regular file, or nullopt when it does not exist or is not a regular file.
std::optional<std::uintmax_t> regularFileSize(const std::filesystem::path& path);

/// The error is the disk filling up (HDF5 and SQLite report errno 28 in their own words).
bool isDiskFull(const std::string& message);

/// Bytes as people read them, with the exact count for machines: "1.9 GiB (2040109465 B)".
std::string formatBytes(double bytes);

/// Bytes free to this process on the filesystem holding `path`, or nullopt when it cannot be told.
std::optional<std::uintmax_t> availableBytes(const std::filesystem::path& path);

}  // namespace rupture::server
