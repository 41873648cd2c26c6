#pragma once
// Helpers shared by every test area.
#include <unistd.h>

#include <filesystem>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "rupture/run.hpp"

namespace rupture::testing {

/// A fresh directory under the system temporary directory, removed at destruction.
class ScratchDir {
public:
  ScratchDir() {
    std::random_device rd;
    m_path = std::filesystem::temp_directory_path() /
             ("rupture-test-" + std::to_string(::getpid()) + "-" + std::to_string(rd()));
    std::filesystem::create_directories(m_path);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(m_path, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return m_path; }
  std::filesystem::path operator/(const std::string& name) const { return m_path / name; }

private:
  std::filesystem::path m_path;
};

/// The field named by the SpecError that validateSpec throws, or "" if it accepts the spec.
inline std::string rejectedField(const nlohmann::json& spec) {
  try {
    validateSpec(spec);
  } catch (const SpecError& e) {
    return e.field();
  }
  return "";
}

}  // namespace rupture::testing
