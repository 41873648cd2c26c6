// rupture-server: the REST job server. Configuration: flags or RUPTURE_* variables (--help).
// SIGTERM / SIGINT stop it gracefully: a dedicated thread waits for them with sigwait (never a
// signal handler) and calls stop(); running runs are re-queued for the next start.
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <thread>

#include <pthread.h>

#include "common/config.hpp"
#include "common/log.hpp"
#include "server.hpp"

#ifndef RUPTURE_VERSION
#define RUPTURE_VERSION "0.0.0"
#endif

int main(int argc, char** argv) {
  using namespace rupture::server;
  std::vector<std::string> args(argv + 1, argv + argc);
  ConfigResult parsed = parseConfig(args, processEnvironment());
  if (!parsed.error.empty()) {
    std::cerr << "rupture-server: " << parsed.error << "\n";
    return 2;
  }
  if (parsed.showHelp) {
    std::cout << helpText();
    return 0;
  }
  if (parsed.showVersion) {
    std::cout << "rupture-server " << RUPTURE_VERSION << "\n";
    return 0;
  }

  // Block the stop signals in every thread (they inherit this mask); only the waiter receives them.
  sigset_t stopSignals;
  sigemptyset(&stopSignals);
  sigaddset(&stopSignals, SIGTERM);
  sigaddset(&stopSignals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &stopSignals, nullptr);

  try {
    RuptureServer server(parsed.config);
    const int port = server.bind();
    // Machine-readable first line on stdout (scripts and tests read the port from it).
    std::printf("rupture-server listening on http://%s:%d\n", parsed.config.bind.c_str(), port);
    std::fflush(stdout);

    std::thread waiter([&] {
      int signal = 0;
      sigwait(&stopSignals, &signal);
      logLine(std::string("received ") + (signal == SIGINT ? "SIGINT" : "SIGTERM") + "; stopping");
      std::thread second([&] {  // a second signal while stopping ends the process at once
        int again = 0;
        sigwait(&stopSignals, &again);
        std::_Exit(130);
      });
      second.detach();
      server.stop();
    });
    const bool ok = server.listen();
    if (!ok) {
      logLine("the HTTP server failed");
      std::_Exit(1);
    }
    waiter.join();
  } catch (const std::exception& e) {
    std::cerr << "rupture-server: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
