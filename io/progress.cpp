#include "io/progress.hpp"

#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <sstream>
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
  std::ostringstream line;
  line << "vcontact: " << what_ << ": " << done;
  if (!unit_.empty()) line << ' ' << unit_;
  if (total_ > 0.0) line << " (" << static_cast<int>(100.0 * done / total_) << "%)";
  const std::string text = line.str();
  std::cerr << '\r' << text << std::string(width_ > text.size() ? width_ - text.size() : 0, ' ')
            << std::flush;
  width_ = text.size();
  printed_ = true;
}

void Progress::update(const std::string& what, double done, double total) {
  if (!shown_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  const bool changed = what != what_;
  what_ = what;
  total_ = total;
  if (changed) last_ = {};  // a new part shows at once
  if (total > 0.0) {
    update(done);
    return;
  }
  // no amount: "what ..." only
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_).count() < kProgressIntervalS) return;
  last_ = now;
  const std::string text = "vcontact: " + what_ + " ...";
  std::cerr << '\r' << text << std::string(width_ > text.size() ? width_ - text.size() : 0, ' ')
            << std::flush;
  width_ = text.size();
  printed_ = true;
}

void Progress::finish() {
  if (printed_) std::cerr << '\n';
  printed_ = false;
}

}  // namespace vcontact::io
