#pragma once
// Bytes made of pieces, each kept in memory or read from a file when asked for: an archive of
// large files streamed over HTTP without holding its members in memory (tar_archive.hpp,
// zip_archive.hpp).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rupture::server {

class PiecedStream {
public:
  void appendBytes(std::string bytes);
  /// `size` bytes of `path` from its start, read when streamed.
  void appendFile(const std::filesystem::path& path, std::uint64_t size);

  std::uint64_t size() const { return m_size; }
  /// Copies up to `length` bytes from `offset` into `out`; returns how many (fewer at the end, or
  /// when a file cannot be read as it was when appended: the stream then stops short).
  std::size_t read(std::uint64_t offset, char* out, std::size_t length) const;

private:
  struct Piece {
    std::uint64_t offset = 0, length = 0;
    std::string bytes;           ///< the piece's bytes, or
    std::filesystem::path file;  ///< a file read from its start (bytes empty)
  };
  std::vector<Piece> m_pieces;
  std::uint64_t m_size = 0;
};

}  // namespace rupture::server
