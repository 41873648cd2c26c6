#pragma once
// Named points of the result commit where a test can kill the server (tests/README.md): with
// RUPTURE_TEST_KILL_AT=<point> in its environment, the process SIGKILLs itself on reaching that
// point, as a power cut or the OOM killer would stop it there. The variable is read once; a point
// costs a comparison, once per run (never in a loop), and nothing without the variable.
#include <csignal>
#include <cstdlib>
#include <string>
#include <string_view>

namespace rupture::server {

/// The commit's points, in order (execution/scheduler.cpp).
namespace kill_point {
inline constexpr std::string_view kAfterEngine = "after-engine";                   // the engine returned, result complete as .part
inline constexpr std::string_view kAfterSummaryTmp = "after-summary-tmp";          // run-k.summary.json.tmp written and synced
inline constexpr std::string_view kAfterSummaryRename = "after-summary-rename";    // run-k.summary.json in place
inline constexpr std::string_view kAfterResultRename = "after-result-rename";      // run-k.h5 in place
inline constexpr std::string_view kAfterCheckpointRemoval = "after-checkpoint-removal";  // before the store
}  // namespace kill_point

inline void killPointForTests(std::string_view point) {
  static const std::string chosen = [] {
    const char* value = std::getenv("RUPTURE_TEST_KILL_AT");
    return value ? std::string(value) : std::string();
  }();
  if (!chosen.empty() && chosen == point) std::raise(SIGKILL);
}

}  // namespace rupture::server
