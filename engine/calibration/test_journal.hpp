#pragma once
// The checkpoints of a run made of quasi-static tests (the elastic-properties scenario: a beam fit,
// a strength test or fit; docs/checkpoints.md). The fits choose their next test from the results
// of the last ones, so the run's state is the journal of the tests finished so far plus the state of
// the test under way: a resumed run replays the finished tests from their recorded results (the
// fits are deterministic, so they ask for the same tests in the same order), and the test under
// way loads its state and continues from the step where the checkpoint was taken.
//
// The journal does not know the file: the run gives it `poll` (the checkpoint and stop decision at
// the top of every relaxation step, numbered over all the run's tests) and `loadLater` (loads a part
// of the checkpoint being resumed, once the test under way has been set up again).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "rupture/state_archive.hpp"

namespace rupture {

class TestJournal {
public:
  using State = std::function<void(StateArchive&)>;
  struct Hooks {
    std::function<bool(std::uint64_t step)> poll;   ///< true: stop here (after a checkpoint if asked)
    std::function<void(const State&)> loadLater;    ///< loads a part of the checkpoint and ends its loading
  };

  explicit TestJournal(Hooks hooks) : m_hooks(std::move(hooks)) {}

  /// The journal and the test under way, as the run's checkpoint state.
  void exchangeState(StateArchive& archive);
  /// After loading: the checkpoint was taken inside a test (its state is loaded by begin()).
  bool resumesInsideATest() const { return m_liveIndex >= 0; }

  /// A test about to start: its result when it finished before the checkpoint (the caller returns it
  /// without running), else nothing (the caller runs it: begin(), poll() every step, finish()).
  template <class Result>
  std::optional<Result> replay() {
    static_assert(std::is_trivially_copyable_v<Result>);  // restored byte for byte, as finish() recorded it
    if (m_replayed >= m_results.size()) return std::nullopt;
    const std::vector<std::uint8_t>& bytes = m_results[m_replayed++];
    Result r;
    if (bytes.size() != sizeof(Result))
      throw CheckpointError("the checkpoint's test " + std::to_string(m_replayed - 1) + " is not the test this run asks for");
    std::memcpy(&r, bytes.data(), sizeof(Result));
    return r;
  }
  /// The test that runs names its state (set up again by the caller before this call); when the
  /// checkpoint was taken inside this test, the state is loaded from it.
  void begin(State live);
  /// At the top of every relaxation step, with the test's own step count: true when the run stops.
  bool poll(std::uint64_t testSteps);
  /// The test finished (not stopped): its result is recorded for a later resume.
  template <class Result>
  void finish(const Result& result, std::uint64_t testSteps) {
    static_assert(std::is_trivially_copyable_v<Result>);
    std::vector<std::uint8_t> bytes(sizeof(Result));
    std::memcpy(bytes.data(), &result, sizeof(Result));
    m_results.push_back(std::move(bytes));
    m_replayed = m_results.size();
    m_stepsBefore += testSteps;
    m_liveSteps = 0;
    m_live = nullptr;
  }
  /// A poll said stop: the tests under way return at once and run no more.
  bool stopped() const { return m_stopped; }
  /// Relaxation steps of the finished tests and of the one under way (the run's step count).
  std::uint64_t steps() const { return m_stepsBefore + m_liveSteps; }

private:
  Hooks m_hooks;
  std::vector<std::vector<std::uint8_t>> m_results;  ///< each finished test's result, as its bytes
  std::size_t m_replayed = 0;                        ///< results handed back by replay()
  std::uint64_t m_stepsBefore = 0;                   ///< steps of the finished tests
  std::uint64_t m_liveSteps = 0;                     ///< steps of the test under way
  std::int64_t m_liveIndex = -1;                     ///< loaded: the test the checkpoint was taken in
  State m_live;
  bool m_stopped = false;
};

}  // namespace rupture
