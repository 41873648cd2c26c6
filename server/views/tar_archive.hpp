#pragma once
// A POSIX ustar archive streamed without holding the members in memory: headers and small text
// members are kept as bytes, large members are read from their file on demand. Used for the
// ParaView bundle of a run (its HDF5 file and its XDMF sidecar in one download).
#include <cstdint>
#include <filesystem>
#include <string>

#include "views/pieced_stream.hpp"

namespace rupture::server {

class TarArchive {
public:
  /// Adds a member with the given bytes. Names are at most 100 bytes of ASCII.
  void addText(const std::string& name, const std::string& bytes, std::int64_t mtime);
  /// Adds a member whose bytes are read from `path` when streamed (its size is taken now; ustar
  /// holds up to 8 GiB - 1 per member, larger throws).
  void addFile(const std::string& name, const std::filesystem::path& path, std::int64_t mtime);

  /// Size of the whole archive, the two zero end blocks included.
  std::uint64_t size() const;

  /// Copies up to `length` bytes from `offset` into `out`; returns how many (0 at the end, or when a
  /// file member cannot be read as it was when added).
  std::size_t read(std::uint64_t offset, char* out, std::size_t length) const;

  /// The 512-byte ustar header of one regular file (exposed for tests).
  static std::string header(const std::string& name, std::uint64_t size, std::int64_t mtime);

private:
  void pad(std::uint64_t length);
  PiecedStream m_stream;
};

}  // namespace rupture::server
