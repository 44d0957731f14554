#include "io/progress.hpp"

#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <utility>

namespace vcontact::io {

bool progressWanted() { return ::isatty(STDERR_FILENO) == 1 && std::getenv("CI") == nullptr; }

Progress::Progress(std::string what, double total, std::string unit, bool quiet)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      total_(total),
      shown_(!quiet && progressWanted()),
      last_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { finish(); }

void Progress::update(double done) {
  if (!shown_) return;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_).count() < kProgressIntervalS) return;
  last_ = now;
  std::cerr << "\rvcontact: " << what_ << ": " << done << ' ' << unit_;
  if (total_ > 0.0) std::cerr << " (" << static_cast<int>(100.0 * done / total_) << "%)";
  std::cerr << "   " << std::flush;
  printed_ = true;
}

void Progress::finish() {
  if (printed_) std::cerr << '\n';
  printed_ = false;
}

}  // namespace vcontact::io
