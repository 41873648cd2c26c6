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
constexpr const char* kCheckpointGroup = "/checkpoint";
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

std::string rankCheckpointPath(const std::string& checkpoint, int rank) {
  return rank == 0 ? checkpoint : checkpoint + ".rank-" + std::to_string(rank);
}

nlohmann::json checkpointSpecIdentity(const nlohmann::json& spec) {
  nlohmann::json identity = spec;
  if (identity.is_object() && identity.contains("run") && identity["run"].is_object()) {
    identity["run"].erase("checkpoint_interval_s");
    identity["run"].erase("ranks");  // how many processes step it, not what it computes (docs/distributed.md)
    if (identity["run"].empty()) identity.erase("run");
  }
  return identity;
}

std::uintmax_t writeCheckpoint(ResultFile& partial, const std::string& path, const CheckpointHeader& header,
                               const std::function<void(StateArchive&)>& save) {
  const std::string temporary = path + ".tmp";
  try {
    // A discarded result (a rank of a decomposed run but the first) is empty: the first rank's
    // checkpoint holds the result, this one the rank's state alone.
    if (!partial.discarded()) partial.copyTo(temporary);
    Hdf5File copy = partial.discarded() ? Hdf5File::create(temporary) : Hdf5File::openReadWrite(temporary);
    copy.remove(kCheckpointGroup);
    copy.createGroup(kCheckpointGroup);
    copy.setAttribute(kCheckpointGroup, "format", kCheckpointFormat);
    copy.setAttribute(kCheckpointGroup, "rupture_version", header.version);
    copy.setAttribute(kCheckpointGroup, "scenario", header.scenario);
    copy.setAttribute(kCheckpointGroup, "spec", header.spec.dump());
    copy.setAttribute(kCheckpointGroup, "step", header.step);
    copy.setAttribute(kCheckpointGroup, "time", header.time);
    copy.setAttribute(kCheckpointGroup, "threads", header.threads);
    copy.setAttribute(kCheckpointGroup, "ranks", header.ranks);
    copy.setAttribute(kCheckpointGroup, "resumes", header.resumes);
    copy.setAttribute(kCheckpointGroup, "wall_time_s", header.wallTime);
    copy.setAttribute(kCheckpointGroup, "written", utcNow());
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
    if (!file.exists(kCheckpointGroup)) throw CheckpointError("the file " + path + " is not a checkpoint (no /checkpoint)");
    const std::int64_t format = file.readAttributeInt(kCheckpointGroup, "format");
    if (format != kCheckpointFormat)
      throw CheckpointError("the checkpoint " + path + " has format " + std::to_string(format) + "; this build reads " +
                            std::to_string(kCheckpointFormat));
    h.version = file.readAttributeString(kCheckpointGroup, "rupture_version");
    h.scenario = file.readAttributeString(kCheckpointGroup, "scenario");
    h.spec = nlohmann::json::parse(file.readAttributeString(kCheckpointGroup, "spec"));
    h.step = file.readAttributeInt(kCheckpointGroup, "step");
    h.time = file.readAttributeDouble(kCheckpointGroup, "time");
    h.threads = file.readAttributeInt(kCheckpointGroup, "threads");
    if (file.hasAttribute(kCheckpointGroup, "ranks")) h.ranks = file.readAttributeInt(kCheckpointGroup, "ranks");
    h.resumes = file.readAttributeInt(kCheckpointGroup, "resumes");
    h.wallTime = file.readAttributeDouble(kCheckpointGroup, "wall_time_s");
    h.written = file.readAttributeString(kCheckpointGroup, "written");
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

void loadCheckpointState(const std::string& path, const std::function<void(StateArchive&)>& load) {
  try {
    Hdf5File file = Hdf5File::openReadOnly(path);
    Hdf5StateArchive archive(file, kStateGroup, Hdf5StateArchive::Mode::Load);
    load(archive);
  } catch (const CheckpointError&) {
    throw;
  } catch (const std::exception& e) {
    throw CheckpointError("the checkpoint " + path + " cannot be read (" + e.what() + ")");
  }
}

void endCheckpointLoading(ResultFile& partial) {
  if (partial.file().exists(kCheckpointGroup)) partial.file().remove(kCheckpointGroup);
}

}  // namespace rupture::io
