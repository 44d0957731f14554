#include "report/snapshot_queue.hpp"

#include <algorithm>
#include <cassert>
#include <utility>

namespace vcontact::report {

SnapshotQueue::SnapshotQueue(std::size_t slots, Consumer consume, std::function<void()> start)
    : ring_(slots),
      consume_(std::move(consume)),
      start_(std::move(start)),
      batch_(std::max<std::size_t>(1, slots / 2)) {
  assert(slots >= 1);
  thread_ = std::thread([this] { consumeAll(); });
}

SnapshotQueue::~SnapshotQueue() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  taken_cv_.notify_one();
  if (thread_.joinable()) thread_.join();
}

void SnapshotQueue::rethrowFailure() const {
  if (failed_.load(std::memory_order_acquire)) std::rethrow_exception(failure_);
}

// The pusher's slow path: the ring is full. It sleeps until the consumer has freed half of it
// (or failed). The flag is set before the count is read again, and the consumer stores its
// count before it reads the flag (both sequentially consistent), so one of the two sees the
// other: no wake-up is lost. The consumer clears the flag when it wakes the pusher, so that a
// pusher slow to be scheduled gets one wake-up, not one per freed slot.
void SnapshotQueue::waitForFree() {
  if (on_full_) on_full_();
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    pusher_waiting_ = true;
    if (pushed_.load() - popped_.load() < ring_.size() || failed_.load()) break;
    freed_cv_.wait(lock);
  }
  pusher_waiting_ = false;
}

void SnapshotQueue::push(const dynamics::Snapshot& s) {
  rethrowFailure();
  const std::size_t pushed = pushed_.load(std::memory_order_relaxed);  // written here only
  if (pushed - popped_.load(std::memory_order_acquire) == ring_.size()) {
    waitForFree();
    rethrowFailure();
  }
  // The consumer reads only slots below pushed_, and this one is not yet.
  ring_[pushed % ring_.size()] = s;
  pushed_.store(pushed + 1);  // sequentially consistent: before the flag is read
  if (pushed + 1 - popped_.load() < batch_ || !consumer_asleep_.exchange(false)) return;
  { const std::lock_guard<std::mutex> lock(mutex_); }  // the sleeper is in wait() or past it
  taken_cv_.notify_one();
}

void SnapshotQueue::finish() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
  }
  taken_cv_.notify_one();
  if (thread_.joinable()) thread_.join();
  rethrowFailure();
}

// The consumer's wait: when the ring is empty it sleeps until half the slots are taken, or the
// run closes or stops (the same handshake as waitForFree, mirrored).
bool SnapshotQueue::waitForTaken(std::size_t& index) {
  const std::size_t popped = popped_.load(std::memory_order_relaxed);  // written here only
  if (pushed_.load(std::memory_order_acquire) == popped) {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      consumer_asleep_ = true;
      if (pushed_.load() - popped >= batch_ || closing_ || stopping_.load()) break;
      taken_cv_.wait(lock);
    }
    consumer_asleep_ = false;
  }
  if (stopping_.load() || pushed_.load(std::memory_order_acquire) == popped) return false;
  index = popped % ring_.size();
  return true;
}

void SnapshotQueue::release(std::size_t popped) {
  popped_.store(popped + 1);  // sequentially consistent: before the flag is read
  const std::size_t free = ring_.size() - (pushed_.load() - popped - 1);
  if (free < batch_ || !pusher_waiting_.exchange(false)) return;
  { const std::lock_guard<std::mutex> lock(mutex_); }
  freed_cv_.notify_one();
}

void SnapshotQueue::fail(std::exception_ptr e) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    failure_ = std::move(e);
    failed_.store(true, std::memory_order_release);
  }
  freed_cv_.notify_one();
}

void SnapshotQueue::consumeAll() {
  try {
    if (start_) start_();
  } catch (...) {
    fail(std::current_exception());
    return;
  }
  std::size_t index = 0;
  while (waitForTaken(index)) {
    try {
      consume_(ring_[index]);
    } catch (...) {
      fail(std::current_exception());
      return;
    }
    release(popped_.load(std::memory_order_relaxed));
  }
}

}  // namespace vcontact::report
