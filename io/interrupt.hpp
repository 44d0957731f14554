#pragma once
// A run asked to stop by the user (Ctrl-C: SIGINT; a job scheduler or `kill`: SIGTERM). One
// flag for the whole process, set by the signal handlers installed here and read by the
// simulator's step loop (dynamics/simulator.cpp), which then stops the run as it stops on an
// error: the rows so far are kept, summary.json says "stop_cause": "interrupted" and the CLI
// exits with 3. A front end that catches the signal itself (Python, which turns SIGINT into
// KeyboardInterrupt) sets the flag with requestInterrupt() from the callback it polls.
//
// The handlers do nothing but store the signal number (async-signal-safe: a lock-free atomic),
// and are installed with SA_RESETHAND: a second signal finds the default action and ends the
// process at once, as a user who presses Ctrl-C twice expects.

namespace vcontact::io {

/// The signal that asked the run to stop (SIGINT, SIGTERM, or what requestInterrupt was
/// given); 0 while none did.
int interruptSignal();

/// Asks the run to stop, as the signal `signal` would (for a front end that catches it itself).
void requestInterrupt(int signal);

/// Forgets a request (before a new run in the same process).
void clearInterrupt();

/// SIGINT and SIGTERM handlers that set the flag, for the lifetime of the object; the
/// constructor clears the flag, the destructor puts back the handlers that were there.
class InterruptHandlers {
 public:
  InterruptHandlers();
  ~InterruptHandlers();
  InterruptHandlers(const InterruptHandlers&) = delete;
  InterruptHandlers& operator=(const InterruptHandlers&) = delete;
};

}  // namespace vcontact::io
