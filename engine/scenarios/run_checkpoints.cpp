#include "scenarios/run_checkpoints.hpp"

#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "core/format_number.hpp"
#include "io/checkpoint_file.hpp"
#include "scenarios/run_support.hpp"

namespace rupture {

RunCheckpoints::RunCheckpoints(RunControl& control, const std::string& resultPath, std::string scenario,
                               const nlohmann::json& inputSpec, double specInterval, Clock::time_point& wallStart)
    : m_control(control),
      m_path(io::checkpointPathFor(resultPath)),
      m_scenario(std::move(scenario)),
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
  io::loadCheckpointState(*m_result, m_state, partsFollow);
  m_partsFollow = partsFollow;
  m_resumes = header.resumes + 1;
  m_wallStart -= std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(header.wallTime));
  m_result->recordResume(header.step);
  m_control.resumedFromStep.store(header.step);
  m_last = Clock::now();
  logStage(m_control, "resumed from the checkpoint at step " + std::to_string(header.step) + ", time " +
                          formatNumber(header.time) + " s (written " + header.written + ")");
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
  header.resumes = m_resumes;
  header.wallTime = std::chrono::duration<double>(began - m_wallStart).count();
  const std::uintmax_t bytes = io::writeCheckpoint(*m_result, m_path, header, m_state);
  m_last = Clock::now();
  const double seconds = std::chrono::duration<double>(m_last - began).count();
  m_control.checkpointStep.store(header.step);
  m_control.checkpointBytes.store(static_cast<double>(bytes));
  m_control.checkpointSeconds.store(seconds);
  logStage(m_control, "checkpoint at step " + std::to_string(step) + ": " + formatNumber(bytes / 1e6) + " MB in " +
                          formatNumber(seconds) + " s");
}

bool RunCheckpoints::tryWrite(std::uint64_t step, double time) {
  try {
    write(step, time);
    return true;
  } catch (const std::exception& e) {
    // A full disk must not end a run that is fine: the previous checkpoint stays as it was.
    logStage(m_control, std::string("cannot write the checkpoint (the run goes on without it): ") + e.what());
    m_last = Clock::now();
    return false;
  }
}

RunCheckpoints::Action RunCheckpoints::poll(std::uint64_t step, double time) {
  if (m_control.cancel.load(std::memory_order_relaxed)) {
    if (m_control.checkpointOnCancel.load() && m_interval > 0) tryWrite(step, time);
    return Action::Stop;
  }
  if (m_control.stopAtStep >= 0 && static_cast<std::int64_t>(step) >= m_control.stopAtStep) {
    tryWrite(step, time);
    return Action::Stop;
  }
  // The clock is read every 16 steps: a step is microseconds to seconds, an interval minutes.
  if (m_interval > 0 && (step & 15) == 0 && Clock::now() - m_last >= std::chrono::duration<double>(m_interval))
    tryWrite(step, time);
  return Action::Continue;
}

void RunCheckpoints::finished(bool completed) {
  if (!completed) return;
  std::error_code ec;
  std::filesystem::remove(m_path, ec);
}

}  // namespace rupture
