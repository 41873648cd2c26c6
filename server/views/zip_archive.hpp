#pragma once
// A ZIP archive (PKWARE APPNOTE 6.3.x) of stored (uncompressed) members, streamed without holding
// them in memory: the RO-Crate of a job (ro_crate.hpp). Stored, because the members that matter are
// HDF5 result files, already compressed where it pays; names are UTF-8 (flag bit 11). No ZIP64:
// a member or an archive of 4 GiB or more is refused (std::length_error), and the server then
// points to the per-run downloads.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "views/pieced_stream.hpp"

namespace rupture::server {

class ZipArchive {
public:
  /// Adds a member with the given bytes.
  void addText(const std::string& name, const std::string& bytes, std::int64_t mtime);
  /// Adds a member read from `path`: its size and CRC-32 are taken now (one read of the file), its
  /// bytes read again when streamed.
  void addFile(const std::string& name, const std::filesystem::path& path, std::int64_t mtime);
  /// Writes the central directory; no member may be added after it.
  void finish();

  std::uint64_t size() const { return m_stream.size(); }
  /// As PiecedStream::read, once finished.
  std::size_t read(std::uint64_t offset, char* out, std::size_t length) const {
    return m_stream.read(offset, out, length);
  }

  /// CRC-32 (ISO 3309, as ZIP uses it), continued from `crc` (0 to start).
  static std::uint32_t crc32(std::string_view bytes, std::uint32_t crc = 0);

private:
  struct Entry {
    std::string name;
    std::uint32_t crc = 0, size = 0, offset = 0;
    std::uint16_t time = 0, date = 0;
  };
  void addHeader(const std::string& name, std::uint64_t size, std::uint32_t crc, std::int64_t mtime);
  PiecedStream m_stream;
  std::vector<Entry> m_entries;
  bool m_finished = false;
};

}  // namespace rupture::server
