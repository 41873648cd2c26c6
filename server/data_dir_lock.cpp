#include "data_dir_lock.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace rupture::server {

DataDirLock::DataDirLock(const std::filesystem::path& dataDir) {
  const std::filesystem::path path = dataDir / kFileName;
  m_fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (m_fd < 0) {
    throw std::runtime_error("cannot open the lock file " + path.string() + ": " + std::strerror(errno));
  }
  if (::flock(m_fd, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    char text[32] = {};
    const ssize_t n = ::pread(m_fd, text, sizeof text - 1, 0);
    ::close(m_fd);
    m_fd = -1;
    std::string owner = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : std::string();
    while (!owner.empty() && (owner.back() == '\n' || owner.back() == ' ')) owner.pop_back();
    if (err == EWOULDBLOCK) {
      throw std::runtime_error("the data directory " + dataDir.string() + " is in use by another rupture-server" +
                               (owner.empty() ? std::string() : " (pid " + owner + ")") +
                               "; stop it or choose another --data-dir");
    }
    throw std::runtime_error("cannot lock " + path.string() + ": " + std::strerror(err));
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(m_fd, 0) != 0 || ::pwrite(m_fd, pid.data(), pid.size(), 0) < 0) {
    // The lock holds without the pid; only the message to a second server is poorer.
  }
}

DataDirLock::~DataDirLock() {
  if (m_fd >= 0) ::close(m_fd);  // closing the descriptor releases the flock
}

}  // namespace rupture::server
