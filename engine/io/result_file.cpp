#include "io/result_file.hpp"

#include <cstdint>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "io/provenance.hpp"
#include "rupture/state_archive.hpp"

namespace rupture::io {

namespace {

bool isCallersTemporary(const std::string& path) {
  constexpr std::string_view kPart = ".part";
  return path.size() > kPart.size() && path.ends_with(kPart);
}

Hdf5File openPartial(const std::string& partPath, const std::string& continueFrom) {
  if (continueFrom.empty()) return Hdf5File::create(partPath);
  try {
    std::filesystem::copy_file(continueFrom, partPath, std::filesystem::copy_options::overwrite_existing);
    return Hdf5File::openReadWrite(partPath);
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove(partPath, ec);
    throw CheckpointError("the checkpoint " + continueFrom + " cannot be read (" + e.what() + ")");
  }
}

}  // namespace

ResultFile::ResultFile(std::string resultPath, const std::string& scenario, const std::string& continueFrom)
    : m_resultPath(std::move(resultPath)),
      m_partPath(isCallersTemporary(m_resultPath) ? m_resultPath : m_resultPath + ".part"),
      m_file(openPartial(m_partPath, continueFrom)),
      m_continued(!continueFrom.empty()) {
  if (m_continued) return;
  m_file.setAttribute("/", "scenario", scenario);
  m_file.setAttribute("/", "rupture_version", std::string(RUPTURE_VERSION));
  m_file.setAttribute("/", "completed", std::int64_t{0});
  writeStartProvenance(m_file);
}

ResultFile::ResultFile(std::string resultPath, const std::string& scenario, Destination destination,
                       const std::string& continueFrom)
    : m_resultPath(std::move(resultPath)),
      m_partPath(destination == Destination::kDisk && !isCallersTemporary(m_resultPath) ? m_resultPath + ".part"
                                                                                       : m_resultPath),
      m_file(destination == Destination::kDisk ? openPartial(m_partPath, continueFrom)
                                               : Hdf5File::createInMemory(m_resultPath + " (in memory)")),
      m_continued(destination == Destination::kDisk && !continueFrom.empty()),
      m_discarded(destination == Destination::kDiscarded) {
  if (m_discarded && !continueFrom.empty())
    throw std::logic_error("ResultFile: a discarded result starts empty; it cannot continue " + continueFrom);
  if (m_continued) return;
  m_file.setAttribute("/", "scenario", scenario);
  m_file.setAttribute("/", "rupture_version", std::string(RUPTURE_VERSION));
  m_file.setAttribute("/", "completed", std::int64_t{0});
  writeStartProvenance(m_file);
}

ResultFile::~ResultFile() {
  if (!m_done) abandon();
}

void ResultFile::writeSpec(const nlohmann::json& resolved, const nlohmann::json& input) {
  m_file.createGroup("/spec");
  m_file.setAttribute("/spec", "json", resolved.dump());
  m_file.setAttribute("/spec", "input", input.dump());
  writeSpecProvenance(m_file, resolved);
}

void ResultFile::writeAttributes(const std::string& group, const nlohmann::json& values,
                                 const std::map<std::string, std::string>& units) {
  m_file.createGroup(group);
  for (const auto& [name, v] : values.items()) {
    if (v.is_boolean()) m_file.setAttribute(group, name, std::int64_t{v.get<bool>() ? 1 : 0});
    else if (v.is_number_integer()) m_file.setAttribute(group, name, v.get<std::int64_t>());
    else if (v.is_number()) m_file.setAttribute(group, name, v.get<double>());
    else if (v.is_string()) m_file.setAttribute(group, name, v.get<std::string>());
    else if (v.is_null()) m_file.setAttribute(group, name, std::numeric_limits<double>::quiet_NaN());
    else m_file.setAttribute(group, name, v.dump());
    if (auto u = units.find(name); u != units.end()) m_file.setAttribute(group, name + "_unit", u->second);
  }
}

void ResultFile::recordResume(std::int64_t step) {
  nlohmann::json steps = nlohmann::json::array();
  if (m_file.hasAttribute("/", "resumed_from_steps"))
    steps = nlohmann::json::parse(m_file.readAttributeString("/", "resumed_from_steps"), nullptr, false);
  if (!steps.is_array()) steps = nlohmann::json::array();
  steps.push_back(step);
  m_file.setAttribute("/", "resumed_from_steps", steps.dump());
  m_file.setAttribute("/", "checkpoint_resumes", static_cast<std::int64_t>(steps.size()));
}

void ResultFile::copyTo(const std::string& path) {
  m_file.close();  // whole on disk
  try {
    std::filesystem::copy_file(m_partPath, path, std::filesystem::copy_options::overwrite_existing);
  } catch (...) {
    m_file.reopenReadWrite();  // a failed copy (a full disk) must not leave the run's own file closed
    throw;
  }
  m_file.reopenReadWrite();
}

void ResultFile::finish(bool completed) {
  m_file.setAttribute("/", "completed", std::int64_t{completed ? 1 : 0});
  writeFinishProvenance(m_file);
  m_file.close();
  if (!m_discarded && m_partPath != m_resultPath) std::filesystem::rename(m_partPath, m_resultPath);
  m_done = true;
}

void ResultFile::abandon() noexcept {
  try {
    m_file.close();
  } catch (...) {
  }
  std::error_code ec;
  if (!m_discarded) std::filesystem::remove(m_partPath, ec);
  m_done = true;
}

}  // namespace rupture::io
