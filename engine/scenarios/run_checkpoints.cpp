#include "scenarios/run_checkpoints.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "core/format_number.hpp"
#include "io/checkpoint_file.hpp"
#include "scenarios/run_support.hpp"
#include "rupture/quantity_text.hpp"

namespace rupture {

namespace {

namespace fs = std::filesystem;

/// HDF5's own writes at the partial result's close (its metadata cache), beyond the data on disk.
constexpr std::uintmax_t kCloseSlackBytes = 1u << 20;

bool isCallersTemporary(const std::string& path) {
  constexpr std::string_view kPart = ".part";
  return path.size() > kPart.size() && path.ends_with(kPart);
}

std::uintmax_t fileSize(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  return ec ? 0 : size;
}

}  // namespace

RunCheckpoints::RunCheckpoints(RunControl& control, const std::string& resultPath, std::string scenario,
                               const nlohmann::json& inputSpec, double specInterval, Clock::time_point& wallStart)
    : m_control(control),
      m_path(io::rankCheckpointPath(io::checkpointPathFor(resultPath), Communicator::world().rank())),
      m_firstRankPath(io::checkpointPathFor(resultPath)),
      m_partialPath(isCallersTemporary(resultPath) ? resultPath : resultPath + ".part"),
      m_scenario(std::move(scenario)),
      m_callerCommits(isCallersTemporary(resultPath)),
      m_specIdentity(io::checkpointSpecIdentity(inputSpec)),
      m_interval(control.checkpointInterval >= 0 ? control.checkpointInterval : specInterval),
      m_wallStart(wallStart),
      m_last(Clock::now()) {}

void RunCheckpoints::attach(io::ResultFile& result, State state) {
  m_result = &result;
  m_state = std::move(state);
  m_last = Clock::now();  // the interval counts from the first step, not from the set-up
}

void RunCheckpoints::restore(bool partsFollow) {
  if (!m_result || !m_state) throw std::logic_error("RunCheckpoints::restore before attach");
  const io::CheckpointHeader header = io::readCheckpointHeader(m_path);
  if (header.ranks != m_comm.size())
    throw CheckpointError("the checkpoint " + m_path + " was written by a run on " + std::to_string(header.ranks) +
                          " rank(s), this one has " + std::to_string(m_comm.size()) + ": each rank saved its own part; resume it with mpirun -np " +
                          std::to_string(header.ranks));
  // Every rank's checkpoint of the same step, or none is taken up (a rank may have had no room).
  const double step = static_cast<double>(header.step);
  if (m_comm.size() > 1 && (m_comm.max(step) != step || -m_comm.max(-step) != step))
    throw CheckpointError("the ranks' checkpoints (" + m_path + " and its siblings) are of different steps; start the run afresh");
  if (m_path == m_firstRankPath) {
    io::loadCheckpointState(*m_result, m_state, partsFollow);
  } else {  // the state in the rank's own file; the result continues the first rank's copy
    if (partsFollow) throw std::logic_error("RunCheckpoints::restore: parts of a state on several ranks");
    io::loadCheckpointState(m_path, m_state);
    io::endCheckpointLoading(*m_result);
  }
  m_partsFollow = partsFollow;
  m_resumes = header.resumes + 1;
  m_wallStart -= std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(header.wallTime));
  m_lastBytes = fileSize(m_path);
  m_lastGoodStep = header.step;
  m_result->recordResume(header.step);
  m_control.resumedFromStep.store(header.step);
  m_last = Clock::now();
  logStage(m_control, "resumed from the checkpoint at step " + std::to_string(header.step) + ", time " +
                          formatQuantity(header.time, "s") + " (written " + header.written + ")");
}

void RunCheckpoints::restorePart(const State& part) {
  if (!m_partsFollow) throw std::logic_error("RunCheckpoints::restorePart without restore(partsFollow)");
  io::loadCheckpointState(*m_result, part);
  m_partsFollow = false;
}

void RunCheckpoints::endRestore() {
  if (!m_partsFollow) return;
  io::endCheckpointLoading(*m_result);
  m_partsFollow = false;
}

void RunCheckpoints::write(std::uint64_t step, double time) {
  if (!m_result || !m_state) throw std::logic_error("RunCheckpoints::write before attach");
  if (m_partsFollow) throw std::logic_error("RunCheckpoints::write while a part of the state is still to load");
  const auto began = Clock::now();
  io::CheckpointHeader header;
  header.scenario = m_scenario;
  header.version = RUPTURE_VERSION;
  header.spec = m_specIdentity;
  header.step = static_cast<std::int64_t>(step);
  header.time = time;
  header.threads = m_control.threads;
  header.ranks = m_comm.size();
  header.resumes = m_resumes;
  header.wallTime = std::chrono::duration<double>(began - m_wallStart).count();
  const std::uintmax_t bytes = io::writeCheckpoint(*m_result, m_path, header, m_state);
  m_lastBytes = bytes;
  m_lastGoodStep = header.step;
  m_last = Clock::now();
  const double seconds = std::chrono::duration<double>(m_last - began).count();
  m_control.checkpointStep.store(header.step);
  m_control.checkpointBytes.store(static_cast<double>(bytes));
  m_control.checkpointSeconds.store(seconds);
  m_control.phases.charge("writing checkpoints", seconds);
  logStage(m_control, "checkpoint at step " + std::to_string(step) + ": " + formatQuantity(bytes / 1e6, "1") + " MB in " +
                          formatQuantity(seconds, "s"));
}

std::uintmax_t RunCheckpoints::bytesForNextCheckpoint() const {
  // The copy of the partial result as it is now, its state (about what the last checkpoint added
  // to its own copy: the last checkpoint's size covers both, the partial result only grows), and
  // what HDF5 still has to write when the partial result is closed for the copy.
  const std::uintmax_t partial = fileSize(m_partialPath);
  if (partial == 0) return 0;
  return partial + std::max(m_lastBytes, partial) + kCloseSlackBytes;
}

bool RunCheckpoints::tryWrite(std::uint64_t step, double time) {
  const std::string kept = m_lastGoodStep >= 0 ? "its last checkpoint (step " + std::to_string(m_lastGoodStep) + ") stays"
                                               : std::string("it has no checkpoint yet");
  // A disk without room for the copy: skipped before the partial result is touched (closing it on
  // a full disk would lose it), so the run goes on as if the interval were longer.
  std::error_code ec;
  const fs::space_info space = fs::space(fs::path(m_path).parent_path().empty() ? fs::path(".") : fs::path(m_path).parent_path(), ec);
  if (const std::uintmax_t needed = bytesForNextCheckpoint(); !ec && needed > 0 && space.available < needed) {
    logStage(m_control, "no room for the checkpoint at step " + std::to_string(step) + " (" +
                            formatNumber(static_cast<double>(space.available) / 1e6) + " MB free, about " +
                            formatNumber(static_cast<double>(needed) / 1e6) + " MB needed): skipped, the run goes on and " + kept);
    m_control.checkpointsSkipped.fetch_add(1);
    m_last = Clock::now();
    return false;
  }
  try {
    write(step, time);
    return true;
  } catch (const std::exception& e) {
    // The partial result closed for good (the disk filled up as HDF5 wrote it out): this attempt
    // cannot go on, its last good checkpoint can. Thrown on, so that the server re-queues the run.
    if (!m_result->file().isOpen())
      throw std::runtime_error(std::string("the disk filled up while the checkpoint at step ") + std::to_string(step) +
                               " was written, and the partial result could not be kept (" + e.what() + "); " + kept);
    // A full disk must not end a run that is fine: the previous checkpoint stays as it was.
    logStage(m_control, std::string("cannot write the checkpoint (the run goes on without it; ") + kept + "): " + e.what());
    m_control.checkpointsSkipped.fetch_add(1);
    m_last = Clock::now();
    return false;
  }
}

RunCheckpoints::Action RunCheckpoints::poll(std::uint64_t step, double time) {
  // This rank's wish: kWrite a checkpoint, kStop, or both.
  constexpr int kWrite = 1, kStop = 2;
  // The clock is read every 16 steps: a step is microseconds to seconds, an interval minutes.
  constexpr std::uint64_t kEvery = 16;
  const bool stopStep = m_control.stopAtStep >= 0 && static_cast<std::int64_t>(step) >= m_control.stopAtStep;
  int wish = 0;
  if (stopStep) {
    wish = kStop | kWrite;  // asked for a checkpoint at that step, cancelled or not
  } else if (m_control.cancel.load(std::memory_order_relaxed)) {
    wish = kStop | (m_control.checkpointOnCancel.load() && m_interval > 0 ? kWrite : 0);
  } else if (m_interval > 0 && step % kEvery == 0 && Clock::now() - m_last >= std::chrono::duration<double>(m_interval)) {
    wish = kWrite;
  }
  // On several ranks --stop-at-step, every rank's argument, is decided by each alone at the same
  // step. The rest is agreed every 16 steps, not every step (a cancel flag stays set until then):
  // every rank does what the most any rank wishes, a stop winning over a checkpoint of the interval
  // alone (3 > 2 > 1), so the ranks' checkpoints are always of the same step.
  if (m_comm.size() > 1 && !stopStep) {
    if (step % kEvery != 0) return Action::Continue;
    wish = static_cast<int>(m_comm.max(static_cast<double>(wish)));
  }
  if (wish & kWrite) tryWrite(step, time);
  return (wish & kStop) ? Action::Stop : Action::Continue;
}

void RunCheckpoints::finished(bool completed) {
  // A caller that commits the result removes the first rank's checkpoint; the other ranks' are
  // theirs to remove.
  if (!completed || (m_callerCommits && m_comm.rank() == 0)) return;
  std::error_code ec;
  std::filesystem::remove(m_path, ec);
}

}  // namespace rupture
