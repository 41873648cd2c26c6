#include "views/tar_archive.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace rupture::server {
namespace {

constexpr std::uint64_t kBlock = 512;
constexpr std::uint64_t kMaxMember = (std::uint64_t{1} << 33) - 1;  // 11 octal digits

/// Octal digits right-aligned in a field of `width` bytes, the last one NUL (ustar numbers).
/// The caller keeps value below 8^(width-1).
void putOctal(char* field, std::size_t width, std::uint64_t value) {
  field[width - 1] = '\0';
  for (std::size_t k = width - 1; k-- > 0;) {
    field[k] = static_cast<char>('0' + (value & 7));
    value >>= 3;
  }
}

}  // namespace

std::string TarArchive::header(const std::string& name, std::uint64_t size, std::int64_t mtime) {
  if (name.empty() || name.size() > 100) throw std::invalid_argument("tar: member name must be 1 to 100 bytes");
  if (size > kMaxMember) throw std::invalid_argument("tar: member '" + name + "' is larger than 8 GiB");
  char h[kBlock];
  std::memset(h, 0, sizeof h);
  std::memcpy(h, name.data(), name.size());                    // name
  putOctal(h + 100, 8, 0644);                                  // mode
  putOctal(h + 108, 8, 0);                                     // uid
  putOctal(h + 116, 8, 0);                                     // gid
  putOctal(h + 124, 12, size);                                 // size
  putOctal(h + 136, 12, static_cast<std::uint64_t>(std::clamp<std::int64_t>(mtime, 0, kMaxMember)));  // mtime
  std::memset(h + 148, ' ', 8);                                // checksum counts as spaces
  h[156] = '0';                                                // regular file
  std::memcpy(h + 257, "ustar", 6);                            // magic "ustar\0"
  std::memcpy(h + 263, "00", 2);                               // version
  std::memcpy(h + 265, "rupture", 7);                          // uname
  std::memcpy(h + 297, "rupture", 7);                          // gname
  unsigned sum = 0;
  for (unsigned char c : h) sum += c;
  std::snprintf(h + 148, 7, "%06o", sum);                      // six digits, NUL, then the space
  h[155] = ' ';
  return std::string(h, sizeof h);
}

void TarArchive::pad(std::uint64_t length) {
  const std::uint64_t rest = length % kBlock;
  if (rest != 0) m_stream.appendBytes(std::string(kBlock - rest, '\0'));
}

void TarArchive::addText(const std::string& name, const std::string& bytes, std::int64_t mtime) {
  m_stream.appendBytes(header(name, bytes.size(), mtime));
  m_stream.appendBytes(bytes);
  pad(bytes.size());
}

void TarArchive::addFile(const std::string& name, const std::filesystem::path& path, std::int64_t mtime) {
  const std::uint64_t size = std::filesystem::file_size(path);
  m_stream.appendBytes(header(name, size, mtime));
  m_stream.appendFile(path, size);
  pad(size);
}

std::uint64_t TarArchive::size() const { return m_stream.size() + 2 * kBlock; }

std::size_t TarArchive::read(std::uint64_t offset, char* out, std::size_t length) const {
  std::size_t done = 0;
  if (offset < m_stream.size()) {
    done = m_stream.read(offset, out, length);
    if (offset + done < m_stream.size()) return done;  // stopped short (or the buffer is full)
  }
  // The two zero end blocks.
  const std::uint64_t at = offset + done;
  const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(length - done, size() > at ? size() - at : 0));
  std::memset(out + done, 0, n);
  return done + n;
}

}  // namespace rupture::server
