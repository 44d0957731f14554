#pragma once
// Progress of a long run (simulate, fit, diagnose, reading a large dataset) on standard error:
// one line, rewritten in place, at most every kProgressIntervalS of wall time. Shown only to a
// person watching: standard error is a terminal and the environment variable CI is not set.
// In a pipe, a log file or CI nothing is printed, so outputs and logs stay the same.

#include <chrono>
#include <mutex>
#include <string>

namespace vcontact::io {

/// Whether progress lines would be seen: stderr is a TTY and CI is unset.
bool progressWanted();

class Progress {
 public:
  /// @param what  the run's name, printed first ("simulate", "reading data.csv")
  /// @param total the amount at completion (seconds simulated, rows, iterations); <= 0 when
  ///              unknown: then only the amount done is shown
  /// @param unit  the amount's unit ("s", "rows"), after the number
  Progress(std::string what, double total, std::string unit, bool quiet = false);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Reports `done`; prints when the last line is older than kProgressIntervalS.
  void update(double done);
  /// The same for a run of several parts (fit, diagnose): `what` names the part now running
  /// ("diagnose: stage 2: candidates fitted"), `total` its own amount (<= 0: unknown).
  /// Thread-safe (fits report from worker threads).
  void update(const std::string& what, double done, double total);
  /// Ends the progress line (a newline), once; also done by the destructor.
  void finish();

  static constexpr double kProgressIntervalS = 0.5;  ///< wall-clock seconds between lines

 private:
  std::string what_, unit_;
  double total_;
  bool shown_;  ///< progress goes to the terminal
  bool printed_ = false;
  std::chrono::steady_clock::time_point last_;
  std::mutex mutex_;
  std::size_t width_ = 0;  ///< of the last line, to blank what a shorter one leaves
};

}  // namespace vcontact::io
