#include "common/files.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace rupture::server {
namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path) {
  throw std::runtime_error(what + " " + path.string() + ": " + std::strerror(errno));
}

void fsyncPath(const std::filesystem::path& path, int flags) {
  int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) fail("cannot open", path);
  if (::fsync(fd) != 0 && errno != EINVAL) {  // EINVAL: the file system cannot sync directories
    ::close(fd);
    fail("cannot fsync", path);
  }
  ::close(fd);
}

}  // namespace

void writeFileSynced(const std::filesystem::path& path, const std::string& content) {
  int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot create", path);
  // A failed write (a full disk) leaves no part behind: the file goes too.
  auto abandon = [&](const char* what) {
    const int err = errno;
    ::close(fd);
    ::unlink(path.c_str());
    errno = err;
    fail(what, path);
  };
  std::size_t done = 0;
  while (done < content.size()) {
    ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      abandon("cannot write");
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) abandon("cannot fsync");
  ::close(fd);
}

void syncFile(const std::filesystem::path& path) { fsyncPath(path, O_RDONLY); }

void writeFileAtomic(const std::filesystem::path& path, const std::string& content) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  writeFileSynced(tmp, content);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) fail("cannot rename to", path);
  fsyncPath(path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path(), O_RDONLY | O_DIRECTORY);
}

void renameDurable(const std::filesystem::path& from, const std::filesystem::path& to) {
  fsyncPath(from, O_RDONLY);
  if (std::rename(from.c_str(), to.c_str()) != 0) fail("cannot rename to", to);
  fsyncPath(to.parent_path().empty() ? std::filesystem::path(".") : to.parent_path(), O_RDONLY | O_DIRECTORY);
}

std::optional<std::string> readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream out;
  out << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return out.str();
}

std::optional<std::uintmax_t> regularFileSize(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || ec) return std::nullopt;
  auto size = std::filesystem::file_size(path, ec);
  if (ec) return std::nullopt;
  return size;
}

bool isDiskFull(const std::string& message) {
  for (const char* sign : {"No space left on device", "errno = 28", "database or disk is full", "Disk quota exceeded"})
    if (message.find(sign) != std::string::npos) return true;
  return false;
}

std::string formatBytes(double bytes) {
  static const char* const units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  double value = bytes;
  int unit = 0;
  while (value >= 1024 && unit < 4) {
    value /= 1024;
    ++unit;
  }
  char text[64];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.3g %s (%.0f B)", value, units[unit], bytes);
  return text;
}

std::optional<std::uintmax_t> availableBytes(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::space_info space = std::filesystem::space(path, ec);
  if (ec) return std::nullopt;
  return space.available;
}

}  // namespace rupture::server
