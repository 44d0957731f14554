#include "io/interrupt.hpp"

#include <signal.h>

#include <atomic>

namespace vcontact::io {
namespace {

std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free,
              "a signal handler may only touch lock-free atomics");

// Previous handlers, put back by ~InterruptHandlers.
struct sigaction g_previous_int {};
struct sigaction g_previous_term {};

extern "C" void onInterrupt(int signal) { g_signal.store(signal, std::memory_order_relaxed); }

}  // namespace

int interruptSignal() { return g_signal.load(std::memory_order_relaxed); }

void requestInterrupt(int signal) { g_signal.store(signal, std::memory_order_relaxed); }

void clearInterrupt() { g_signal.store(0, std::memory_order_relaxed); }

InterruptHandlers::InterruptHandlers() {
  clearInterrupt();
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_RESTART;  // a second signal: the default action, at once
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

InterruptHandlers::~InterruptHandlers() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

}  // namespace vcontact::io
