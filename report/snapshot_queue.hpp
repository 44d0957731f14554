#pragma once
// The hand-over of a simulation's output snapshots from the stepping thread to one consumer
// thread (report/async_simulation_csv.hpp): a fixed ring of Snapshot slots, filled by copy on
// the stepping thread and emptied in order by the consumer.
//
// - Bounded: the ring's slots are made once; a snapshot is copied into a free slot (the
//   vectors inside keep their capacity, so a warm ring copies without allocating). When every
//   slot is taken (a slow disk), push() waits for the consumer: back-pressure, not growth.
// - Batched: a consumer that has emptied the ring sleeps until half its slots are taken (or
//   the run ends) and then writes all it finds; the pusher, held by a full ring, is woken
//   when half is free again. A wake-up per snapshot (a futex call and a context switch,
//   microseconds) would cost more than ball_drop's formatting of one output time.
// - Failures: the consumer's first exception is kept; the consumer stops, and push() and
//   finish() rethrow it on the stepping thread (the same exception object, so the same type
//   and message as a synchronous writer's).
// - The consumer runs on a std::thread of its own, not a TBB task: it spends its life waiting
//   on a condition variable, which would take a worker from the pool the contact queries'
//   parallel loops share.

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "dynamics/simulation_output.hpp"

namespace vcontact::report {

class SnapshotQueue {
 public:
  using Consumer = std::function<void(const dynamics::Snapshot&)>;

  /// Makes `slots` snapshot slots and starts the consumer thread, which calls `start` (when
  /// given: the consumer's own set-up, such as opening its files) and then `consume` on each
  /// pushed snapshot in order. An exception from `start` is a failure like one from `consume`.
  /// @pre slots >= 1
  SnapshotQueue(std::size_t slots, Consumer consume, std::function<void()> start = {});
  /// Stops the consumer after the snapshot it is on (those still queued are dropped: a run
  /// abandoned by an exception commits nothing) and joins it.
  ~SnapshotQueue();
  SnapshotQueue(const SnapshotQueue&) = delete;
  SnapshotQueue& operator=(const SnapshotQueue&) = delete;

  /// Copies `s` into a free slot, waiting while every slot is taken.
  /// @throws the consumer's first exception once it has thrown (then `s` is not queued)
  void push(const dynamics::Snapshot& s);
  /// Lets the consumer take every queued snapshot, then joins it. Pushing after is an error.
  /// @throws the consumer's first exception when it threw
  void finish();

  std::size_t slots() const { return ring_.size(); }
  /// Test hook: called on the pushing thread when push() finds every slot taken, before it
  /// waits (a test's consumer that holds its first snapshot can then be let go).
  void setFullHook(std::function<void()> hook) { on_full_ = std::move(hook); }

 private:
  void consumeAll();
  /// Waits for work; the slot index of the next snapshot, or none (the ring is closing and
  /// empty, or stopping).
  bool waitForTaken(std::size_t& index);
  void waitForFree();
  void release(std::size_t popped);
  void fail(std::exception_ptr e);
  void rethrowFailure() const;

  std::vector<dynamics::Snapshot> ring_;
  Consumer consume_;
  std::function<void()> start_;
  std::function<void()> on_full_;
  std::size_t batch_ = 1;  ///< half the slots (at least one): see "Batched"
  // One pusher and one consumer: the counts are atomics, each written by one side only, so
  // that a hand-over takes no lock; the mutex is taken only to sleep and to wake a sleeper.
  // Snapshots pushed and written so far (the ring's slot is the count modulo its size); on
  // cache lines of their own, each written by one thread.
  alignas(64) std::atomic<std::size_t> pushed_{0};
  alignas(64) std::atomic<std::size_t> popped_{0};
  alignas(64) std::atomic<bool> consumer_asleep_{false};  ///< waiting for batch_ taken slots
  std::atomic<bool> pusher_waiting_{false};               ///< waiting for batch_ free slots
  std::atomic<bool> stopping_{false};                     ///< the destructor: stop after this one
  std::atomic<bool> failed_{false};                       ///< failure_ is set
  std::mutex mutex_;
  std::condition_variable taken_cv_;  ///< slots were filled, or closing/stopping was set
  std::condition_variable freed_cv_;  ///< slots were freed, or the consumer failed
  bool closing_ = false;              ///< finish(): take the rest, then return (under mutex_)
  std::exception_ptr failure_;        ///< the consumer's first exception (under mutex_)
  std::thread thread_;                ///< last: started once every member above exists
};

}  // namespace vcontact::report
