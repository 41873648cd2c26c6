#include "calibration/test_journal.hpp"

namespace rupture {

namespace {
constexpr const char* kGroup = "test_journal";
constexpr const char* kLiveGroup = "test_under_way";
}  // namespace

void TestJournal::exchangeState(StateArchive& archive) {
  StateGroup group(archive, kGroup);
  std::size_t finished = m_results.size();
  archive.value("finished_tests", finished);
  if (archive.loading()) m_results.resize(finished);
  for (std::size_t k = 0; k < finished; ++k) archive.array("result_" + std::to_string(k), m_results[k]);
  archive.value("steps_of_finished_tests", m_stepsBefore);
  // The index of the test under way (-1: the checkpoint fell between tests).
  std::int64_t live = m_live ? static_cast<std::int64_t>(m_results.size()) : -1;
  archive.value("test_under_way", live);
  if (archive.loading()) {
    m_liveIndex = live;
    m_replayed = 0;
    if (live >= 0 && static_cast<std::size_t>(live) != finished)
      throw CheckpointError("the checkpoint's test under way (" + std::to_string(live) + ") does not follow its " +
                            std::to_string(finished) + " finished tests");
    return;  // the live test's state is loaded by begin(), once the test is set up
  }
  if (m_live) {
    StateGroup liveGroup(archive, kLiveGroup);
    m_live(archive);
  }
}

void TestJournal::begin(State live) {
  m_live = std::move(live);
  m_liveSteps = 0;
  if (m_liveIndex >= 0 && static_cast<std::size_t>(m_liveIndex) == m_results.size()) {
    m_liveIndex = -1;
    m_hooks.loadLater([this](StateArchive& archive) {
      StateGroup group(archive, kGroup);
      StateGroup liveGroup(archive, kLiveGroup);
      m_live(archive);
    });
  }
}

bool TestJournal::poll(std::uint64_t testSteps) {
  m_liveSteps = testSteps;
  if (!m_stopped && m_hooks.poll(steps())) m_stopped = true;
  return m_stopped;
}

}  // namespace rupture
