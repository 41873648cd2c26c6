#pragma once
// SIGINT and SIGTERM as a cancel request, for the commands that run simulations (run,
// validate-suite): the first signal sets the run's cancel flag, a second one kills.
#include <signal.h>

#include <atomic>

namespace rupture::cli {

namespace detail {
// The cancel flag of the run in flight, for the signal handler (std::atomic<bool> is lock-free,
// so storing to it is async-signal-safe).
inline std::atomic<bool>* g_cancel = nullptr;
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" inline void onInterrupt(int) {
  if (g_cancel) g_cancel->store(true);
}

}  // namespace detail

/// Installs the SIGINT handler for the lifetime of a run; SA_RESETHAND: a second Ctrl-C kills.
class InterruptGuard {
public:
  explicit InterruptGuard(std::atomic<bool>& cancel) {
    detail::g_cancel = &cancel;
    struct sigaction action {};
    action.sa_handler = detail::onInterrupt;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;
    sigaction(SIGINT, &action, &m_previousInt);
    sigaction(SIGTERM, &action, &m_previousTerm);
  }
  ~InterruptGuard() {
    sigaction(SIGINT, &m_previousInt, nullptr);
    sigaction(SIGTERM, &m_previousTerm, nullptr);
    detail::g_cancel = nullptr;
  }

private:
  struct sigaction m_previousInt {}, m_previousTerm {};
};

}  // namespace rupture::cli
