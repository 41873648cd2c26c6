#include "views/pieced_stream.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>

namespace rupture::server {

void PiecedStream::appendBytes(std::string bytes) {
  if (bytes.empty()) return;
  const std::uint64_t length = bytes.size();
  m_pieces.push_back(Piece{m_size, length, std::move(bytes), {}});
  m_size += length;
}

void PiecedStream::appendFile(const std::filesystem::path& path, std::uint64_t size) {
  if (size == 0) return;
  m_pieces.push_back(Piece{m_size, size, {}, path});
  m_size += size;
}

std::size_t PiecedStream::read(std::uint64_t offset, char* out, std::size_t length) const {
  std::size_t done = 0;
  while (done < length && offset < m_size) {
    auto it = std::upper_bound(m_pieces.begin(), m_pieces.end(), offset,
                               [](std::uint64_t o, const Piece& p) { return o < p.offset; });
    const Piece& piece = *std::prev(it);  // pieces tile [0, size) from offset 0
    const std::uint64_t within = offset - piece.offset;
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(length - done, piece.length - within));
    if (piece.file.empty()) {
      std::memcpy(out + done, piece.bytes.data() + within, n);
    } else {
      std::ifstream in(piece.file, std::ios::binary);
      in.seekg(static_cast<std::streamoff>(within));
      in.read(out + done, static_cast<std::streamsize>(n));
      if (in.gcount() != static_cast<std::streamsize>(n)) return done;  // the file shrank: stop short
    }
    done += n;
    offset += n;
  }
  return done;
}

}  // namespace rupture::server
