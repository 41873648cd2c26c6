#include "views/zip_archive.hpp"

#include <array>
#include <ctime>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace rupture::server {

namespace {

constexpr std::uint64_t kMax32 = std::numeric_limits<std::uint32_t>::max();
constexpr std::uint16_t kVersion = 20;       // 2.0: stored members, no ZIP64
constexpr std::uint16_t kUtf8Names = 0x0800;  // general purpose bit 11
constexpr std::uint16_t kMadeOnUnix = 3 << 8;

void put16(std::string& out, std::uint16_t v) {
  out.push_back(static_cast<char>(v & 0xff));
  out.push_back(static_cast<char>(v >> 8));
}
void put32(std::string& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
}

const std::array<std::uint32_t, 256>& crcTable() {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  return table;
}

/// MS-DOS time and date of a UTC time (2-second resolution; before 1980 clamps to 1980-01-01).
std::pair<std::uint16_t, std::uint16_t> dosTime(std::int64_t mtime) {
  const std::time_t t = static_cast<std::time_t>(mtime);
  std::tm utc{};
  gmtime_r(&t, &utc);
  if (utc.tm_year < 80) return {0, static_cast<std::uint16_t>((1 << 5) | 1)};
  const auto time = static_cast<std::uint16_t>((utc.tm_hour << 11) | (utc.tm_min << 5) | (utc.tm_sec / 2));
  const auto date = static_cast<std::uint16_t>(((utc.tm_year - 80) << 9) | ((utc.tm_mon + 1) << 5) | utc.tm_mday);
  return {time, date};
}

}  // namespace

std::uint32_t ZipArchive::crc32(std::string_view bytes, std::uint32_t crc) {
  const auto& table = crcTable();
  crc = ~crc;
  for (unsigned char b : bytes) crc = table[(crc ^ b) & 0xff] ^ (crc >> 8);
  return ~crc;
}

void ZipArchive::addHeader(const std::string& name, std::uint64_t size, std::uint32_t crc, std::int64_t mtime) {
  if (m_finished) throw std::logic_error("zip: member added after finish()");
  if (name.empty() || name.size() > 0xffff) throw std::invalid_argument("zip: a member name is 1 to 65535 bytes");
  if (size >= kMax32 || m_stream.size() >= kMax32 || m_entries.size() >= 0xffff)
    throw std::length_error("zip: '" + name + "' would take the archive past 4 GiB or 65535 members");
  const auto [time, date] = dosTime(mtime);
  Entry e{name, crc, static_cast<std::uint32_t>(size), static_cast<std::uint32_t>(m_stream.size()), time, date};
  std::string h;
  put32(h, 0x04034b50);  // local file header
  put16(h, kVersion);
  put16(h, kUtf8Names);
  put16(h, 0);  // stored
  put16(h, e.time);
  put16(h, e.date);
  put32(h, e.crc);
  put32(h, e.size);  // compressed = uncompressed
  put32(h, e.size);
  put16(h, static_cast<std::uint16_t>(name.size()));
  put16(h, 0);  // no extra field
  h += name;
  m_stream.appendBytes(std::move(h));
  m_entries.push_back(std::move(e));
}

void ZipArchive::addText(const std::string& name, const std::string& bytes, std::int64_t mtime) {
  addHeader(name, bytes.size(), crc32(bytes), mtime);
  m_stream.appendBytes(bytes);
}

void ZipArchive::addFile(const std::string& name, const std::filesystem::path& path, std::int64_t mtime) {
  const std::uint64_t size = std::filesystem::file_size(path);
  if (size >= kMax32) throw std::length_error("zip: '" + name + "' is 4 GiB or larger");
  std::ifstream in(path, std::ios::binary);
  std::vector<char> buffer(1 << 20);
  std::uint32_t crc = 0;
  std::uint64_t read = 0;
  while (in && read < size) {
    in.read(buffer.data(), static_cast<std::streamsize>(std::min<std::uint64_t>(buffer.size(), size - read)));
    const auto n = static_cast<std::size_t>(in.gcount());
    crc = crc32(std::string_view(buffer.data(), n), crc);
    read += n;
  }
  if (read != size) throw std::runtime_error("zip: cannot read " + path.filename().string());
  addHeader(name, size, crc, mtime);
  m_stream.appendFile(path, size);
}

void ZipArchive::finish() {
  if (m_finished) return;
  const std::uint64_t directoryOffset = m_stream.size();
  std::string d;
  for (const Entry& e : m_entries) {
    put32(d, 0x02014b50);  // central directory header
    put16(d, kMadeOnUnix | kVersion);
    put16(d, kVersion);
    put16(d, kUtf8Names);
    put16(d, 0);
    put16(d, e.time);
    put16(d, e.date);
    put32(d, e.crc);
    put32(d, e.size);
    put32(d, e.size);
    put16(d, static_cast<std::uint16_t>(e.name.size()));
    put16(d, 0);  // extra
    put16(d, 0);  // comment
    put16(d, 0);  // disk
    put16(d, 0);  // internal attributes
    put32(d, 0100644u << 16);  // external: a regular file, rw-r--r--
    put32(d, e.offset);
    d += e.name;
  }
  if (directoryOffset + d.size() >= kMax32) throw std::length_error("zip: the archive would be 4 GiB or larger");
  const auto count = static_cast<std::uint16_t>(m_entries.size());
  const auto directorySize = static_cast<std::uint32_t>(d.size());
  put32(d, 0x06054b50);  // end of central directory
  put16(d, 0);
  put16(d, 0);
  put16(d, count);
  put16(d, count);
  put32(d, directorySize);
  put32(d, static_cast<std::uint32_t>(directoryOffset));
  put16(d, 0);  // comment
  m_stream.appendBytes(std::move(d));
  m_finished = true;
}

}  // namespace rupture::server
