// report::SnapshotQueue: snapshots reach the consumer whole and in order, a full ring holds the
// pusher back instead of growing, and the consumer's first exception comes back to the pusher.
// No test waits on a clock: where a test needs the consumer held, it holds it on a gate that
// only the test opens.

#include "report/snapshot_queue.hpp"

#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace {

using vcontact::dynamics::Snapshot;
using vcontact::report::SnapshotQueue;

// A snapshot that tells itself apart: time k and k % 3 + 1 bodies (vectors of changing size,
// copied into slots that held others).
Snapshot numbered(int k) {
  Snapshot s;
  s.t = k;
  s.bodies.resize(static_cast<std::size_t>(k % 3 + 1));
  s.bodies.back().w_WB.x() = 10.0 * k;
  return s;
}

// A door the consumer waits at until the test opens it.
class Gate {
 public:
  void open() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      open_ = true;
    }
    cv_.notify_all();
  }
  void pass() {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait(lock, [&] { return open_; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool open_ = false;
};

TEST(SnapshotQueue, SnapshotsReachTheConsumerWholeAndInOrder) {
  constexpr int kCount = 200;  // many times the ring: every slot is reused
  std::vector<Snapshot> seen;
  {
    SnapshotQueue queue(4, [&](const Snapshot& s) { seen.push_back(s); });
    for (int k = 0; k < kCount; ++k) queue.push(numbered(k));
    queue.finish();
  }
  ASSERT_EQ(seen.size(), static_cast<std::size_t>(kCount));
  for (int k = 0; k < kCount; ++k) {
    const Snapshot& s = seen[static_cast<std::size_t>(k)];
    EXPECT_EQ(s.t, k);
    ASSERT_EQ(s.bodies.size(), static_cast<std::size_t>(k % 3 + 1)) << k;
    EXPECT_EQ(s.bodies.back().w_WB.x(), 10.0 * k);
  }
}

// The consumer holds the first snapshot at the gate, so none is written: N pushes fill the N
// slots (that first one included) and must not find the ring full; push N + 1 must, and waits
// (the hook opens the gate) instead of taking an (N + 1)-th slot. Every snapshot still arrives,
// in order.
TEST(SnapshotQueue, AFullRingHoldsThePusherInsteadOfGrowing) {
  constexpr std::size_t kSlots = 5;
  Gate gate;
  std::vector<double> times;
  SnapshotQueue queue(kSlots, [&](const Snapshot& s) {
    if (s.t == 0.0) gate.pass();
    times.push_back(s.t);
  });
  int pushed = 0, full_at = -1, full_calls = 0;
  queue.setFullHook([&] {
    if (full_calls++ == 0) full_at = pushed;
    gate.open();
  });
  for (; pushed < static_cast<int>(kSlots) + 3; ++pushed) queue.push(numbered(pushed));
  queue.finish();
  EXPECT_EQ(queue.slots(), kSlots);
  EXPECT_EQ(full_at, static_cast<int>(kSlots));  // the first push that found no free slot
  ASSERT_EQ(times.size(), kSlots + 3);
  for (std::size_t k = 0; k < times.size(); ++k) EXPECT_EQ(times[k], static_cast<double>(k));
}

// The consumer fails on the snapshot at t = 3: the pusher gets that exception at a later push
// (at most a ring's worth later: the ring cannot take more without the consumer), then again
// at finish(); the consumer sees nothing after the one that failed.
TEST(SnapshotQueue, TheConsumersFirstFailureComesBackToThePusher) {
  constexpr std::size_t kSlots = 4;
  std::vector<double> times;
  SnapshotQueue queue(kSlots, [&](const Snapshot& s) {
    times.push_back(s.t);
    if (s.t == 3.0) throw std::runtime_error("pair_a.csv: write failed (No space left on device)");
  });
  int accepted = 0;
  std::string message;
  try {
    for (; accepted < 1000; ++accepted) queue.push(numbered(accepted));
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  EXPECT_EQ(message, "pair_a.csv: write failed (No space left on device)");
  // 0–2 written, 3 failed, and at most the ring's other slots filled behind it
  EXPECT_GE(accepted, 4);
  EXPECT_LE(accepted, static_cast<int>(3 + kSlots));
  EXPECT_THROW(queue.push(numbered(accepted)), std::runtime_error);
  try {
    queue.finish();
    ADD_FAILURE() << "finish() did not rethrow";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
  EXPECT_EQ(times, (std::vector<double>{0, 1, 2, 3}));
}

// A failure in the consumer's set-up (opening its files) is a failure like a write's: the
// consumer never runs, and the pusher gets the exception at finish() at the latest.
TEST(SnapshotQueue, AFailedStartComesBackToThePusher) {
  int consumed = 0;
  SnapshotQueue queue(
      4, [&](const Snapshot&) { ++consumed; },
      [] { throw std::runtime_error("out: cannot create the output folder"); });
  bool thrown = false;
  try {
    for (int k = 0; k < 10; ++k) queue.push(numbered(k));
    queue.finish();
  } catch (const std::runtime_error& e) {
    thrown = true;
    EXPECT_EQ(std::string(e.what()), "out: cannot create the output folder");
  }
  EXPECT_TRUE(thrown);
  EXPECT_EQ(consumed, 0);
}

}  // namespace
