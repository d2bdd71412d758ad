#include "cli/signals.hpp"

#include <csignal>

namespace sm::cli {
namespace {

constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

std::atomic<bool> g_stop{false};
volatile std::sig_atomic_t g_signal = 0;  // the first stop signal received

void set_handlers(void (*handler)(int)) {
  struct sigaction action {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  for (int sig : kStopSignals) ::sigaction(sig, &action, nullptr);
}

extern "C" void on_stop_signal(int sig) {
  if (g_signal == 0) g_signal = sig;
  g_stop.store(true);
  // A second one ends the program at once (the default action): files stay complete anyway.
  set_handlers(SIG_DFL);
}

}  // namespace

void ignore_broken_pipes() {
  struct sigaction action {};
  action.sa_handler = SIG_IGN;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGPIPE, &action, nullptr);
}

void catch_stop_signals(bool on) {
  set_handlers(on ? on_stop_signal : SIG_DFL);
}

const std::atomic<bool>& stop_requested() {
  return g_stop;
}

int stop_signal() {
  return g_signal;
}

int stopped_exit_code(int sig) {
  return 128 + (sig == 0 ? SIGINT : sig);
}

const char* stopped_text(int sig) {
  switch (sig) {
    case SIGTERM:
      return "terminated (SIGTERM)";
    case SIGHUP:
      return "hung up (SIGHUP)";
    default:
      return "interrupted";
  }
}

}  // namespace sm::cli
