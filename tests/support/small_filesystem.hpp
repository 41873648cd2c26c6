#pragma once
// A small real filesystem for full-disk tests: a tmpfs of a given size mounted on a fresh directory
// (needs CAP_SYS_ADMIN, as root in CI has), unmounted at destruction. Tests skip with the reason
// where it cannot be mounted.
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace rupture::testing {

class SmallFilesystem {
public:
  explicit SmallFilesystem(std::size_t bytes) {
    std::random_device rd;
    m_path = std::filesystem::temp_directory_path() /
             ("rupture-smallfs-" + std::to_string(::getpid()) + "-" + std::to_string(rd()));
    std::filesystem::create_directories(m_path);
    const std::string options = "size=" + std::to_string(bytes);
    if (::mount("tmpfs", m_path.c_str(), "tmpfs", 0, options.c_str()) == 0) m_mounted = true;
    else m_whyNot = std::string("cannot mount a tmpfs here (") + std::strerror(errno) + "); needs root";
  }
  ~SmallFilesystem() {
    if (m_mounted) ::umount2(m_path.c_str(), MNT_DETACH);
    std::error_code ec;
    std::filesystem::remove_all(m_path, ec);
  }
  SmallFilesystem(const SmallFilesystem&) = delete;
  SmallFilesystem& operator=(const SmallFilesystem&) = delete;

  bool mounted() const { return m_mounted; }
  const std::string& whyNot() const { return m_whyNot; }
  const std::filesystem::path& path() const { return m_path; }

  /// Writes `file` until the filesystem is full, leaving at most `keepFree` bytes.
  static void fillUp(const std::filesystem::path& file, std::uintmax_t keepFree = 0) {
    std::ofstream out(file, std::ios::binary);
    const std::vector<char> block(4096, 'x');
    while (out) {
      const auto space = std::filesystem::space(file.parent_path());
      if (space.available <= keepFree + block.size()) break;
      out.write(block.data(), static_cast<std::streamsize>(block.size()));
      out.flush();
    }
  }

private:
  std::filesystem::path m_path;
  bool m_mounted = false;
  std::string m_whyNot;
};

}  // namespace rupture::testing
