#include "io/checkpoint_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <string_view>
#include <system_error>

#include "io/hdf5_state_archive.hpp"
#include "io/provenance.hpp"

namespace rupture::io {

namespace {

namespace fs = std::filesystem;
constexpr const char* kGroup = "/checkpoint";
constexpr const char* kStateGroup = "/checkpoint/state";

/// Flushes a file (or a directory's entries) to the disk: a checkpoint renamed into place must
/// survive a power cut, not only a killed process.
void syncToDisk(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  [[maybe_unused]] const int rc = ::fsync(fd);
  ::close(fd);
}

/// The first differing path of two JSON values, for the refusal message ("" when equal).
std::string firstDifference(const nlohmann::json& a, const nlohmann::json& b) {
  const nlohmann::json patch = nlohmann::json::diff(a, b);
  if (patch.empty()) return "";
  std::string where = patch.front().value("path", std::string("/"));
  for (char& c : where) if (c == '/') c = '.';
  return where.size() > 1 ? where.substr(1) : "(the whole spec)";
}

}  // namespace

std::string checkpointPathFor(const std::string& resultPath) {
  constexpr std::string_view kPart = ".part";
  std::string base = resultPath;
  if (base.size() > kPart.size() && base.ends_with(kPart)) base.resize(base.size() - kPart.size());
  return base + ".checkpoint";
}

nlohmann::json checkpointSpecIdentity(const nlohmann::json& spec) {
  nlohmann::json identity = spec;
  if (identity.is_object() && identity.contains("run") && identity["run"].is_object()) {
    identity["run"].erase("checkpoint_interval_s");
    if (identity["run"].empty()) identity.erase("run");
  }
  return identity;
}

std::uintmax_t writeCheckpoint(ResultFile& partial, const std::string& path, const CheckpointHeader& header,
                               const std::function<void(StateArchive&)>& save) {
  const std::string temporary = path + ".tmp";
  try {
    partial.copyTo(temporary);
    Hdf5File copy = Hdf5File::openReadWrite(temporary);
    copy.remove(kGroup);
    copy.createGroup(kGroup);
    copy.setAttribute(kGroup, "format", kCheckpointFormat);
    copy.setAttribute(kGroup, "rupture_version", header.version);
    copy.setAttribute(kGroup, "scenario", header.scenario);
    copy.setAttribute(kGroup, "spec", header.spec.dump());
    copy.setAttribute(kGroup, "step", header.step);
    copy.setAttribute(kGroup, "time", header.time);
    copy.setAttribute(kGroup, "threads", header.threads);
    copy.setAttribute(kGroup, "resumes", header.resumes);
    copy.setAttribute(kGroup, "wall_time_s", header.wallTime);
    copy.setAttribute(kGroup, "written", utcNow());
    Hdf5StateArchive archive(copy, kStateGroup, Hdf5StateArchive::Mode::Save);
    save(archive);
    copy.close();
    syncToDisk(temporary);
    fs::rename(temporary, path);
    syncToDisk(fs::path(path).parent_path().empty() ? "." : fs::path(path).parent_path().string());
  } catch (...) {
    std::error_code ec;
    fs::remove(temporary, ec);
    throw;
  }
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  return ec ? 0 : size;
}

CheckpointHeader readCheckpointHeader(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw CheckpointError("no checkpoint at " + path);
  CheckpointHeader h;
  try {
    Hdf5File file = Hdf5File::openReadOnly(path);
    if (!file.exists(kGroup)) throw CheckpointError("the file " + path + " is not a checkpoint (no /checkpoint)");
    const std::int64_t format = file.readAttributeInt(kGroup, "format");
    if (format != kCheckpointFormat)
      throw CheckpointError("the checkpoint " + path + " has format " + std::to_string(format) + "; this build reads " +
                            std::to_string(kCheckpointFormat));
    h.version = file.readAttributeString(kGroup, "rupture_version");
    h.scenario = file.readAttributeString(kGroup, "scenario");
    h.spec = nlohmann::json::parse(file.readAttributeString(kGroup, "spec"));
    h.step = file.readAttributeInt(kGroup, "step");
    h.time = file.readAttributeDouble(kGroup, "time");
    h.threads = file.readAttributeInt(kGroup, "threads");
    h.resumes = file.readAttributeInt(kGroup, "resumes");
    h.wallTime = file.readAttributeDouble(kGroup, "wall_time_s");
    h.written = file.readAttributeString(kGroup, "written");
    if (!file.exists(kStateGroup)) throw CheckpointError("the checkpoint " + path + " holds no state");
  } catch (const CheckpointError&) {
    throw;
  } catch (const std::exception& e) {
    throw CheckpointError("the checkpoint " + path + " cannot be read (" + e.what() + ")");
  }
  return h;
}

void checkCheckpointFits(const CheckpointHeader& found, const std::string& path, const std::string& scenario,
                         const nlohmann::json& spec) {
  if (found.scenario != scenario)
    throw CheckpointError("the checkpoint " + path + " is of a " + found.scenario + " run, not " + scenario);
  if (found.version != RUPTURE_VERSION)
    throw CheckpointError("the checkpoint " + path + " was written by rupture " + found.version + "; this is " +
                          RUPTURE_VERSION + ", whose state may differ");
  const nlohmann::json identity = checkpointSpecIdentity(spec);
  if (found.spec != identity)
    throw CheckpointError("the checkpoint " + path + " belongs to another spec (they differ at " +
                          firstDifference(found.spec, identity) + ")");
}

void loadCheckpointState(ResultFile& partial, const std::function<void(StateArchive&)>& load, bool more) {
  Hdf5StateArchive archive(partial.file(), kStateGroup, Hdf5StateArchive::Mode::Load);
  try {
    load(archive);
  } catch (const CheckpointError&) {
    throw;
  } catch (const Hdf5Error& e) {
    throw CheckpointError(std::string("the checkpoint's state cannot be read (") + e.what() + ")");
  }
  if (!more) endCheckpointLoading(partial);
}

void endCheckpointLoading(ResultFile& partial) {
  if (partial.file().exists(kGroup)) partial.file().remove(kGroup);
}

}  // namespace rupture::io
