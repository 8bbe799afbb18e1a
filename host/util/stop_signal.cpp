#include "util/stop_signal.h"

#include <atomic>
#include <csignal>
#include <unistd.h>

namespace repose {

namespace {

std::atomic<int> g_signal{0};

extern "C" void on_stop_signal(int signo) {
  if (g_signal.exchange(signo) != 0) _exit(128 + signo);  // asked twice: stop now
}

}  // namespace

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int stop_requested() { return g_signal.load(); }

}  // namespace repose
