#pragma once
// The simulation's CSV output written on a thread of its own (issue 18, item 4): the stepping
// thread hands each output snapshot over (a copy into a slot of a SnapshotQueue) and steps on,
// while a writer thread opens the files, then formats and writes each snapshot with
// SimulationCsvWriter. The files are those of SimulationCsvWriter, byte for byte, committed
// together with summary.json as before. A failure on the writer thread (a folder that cannot
// be made, a full disk) reaches the stepping thread as the same InputError, at its next
// hand-over or at commit(), and no file of the run is left then.
//
// With OutputThread::kOff everything happens on the calling thread, as SimulationCsvWriter
// alone does (`vcontact simulate --output-thread off`: debugging, and the benchmark's
// reference); the constructor then throws what SimulationCsvWriter's throws.

#include <cstddef>
#include <optional>
#include <string>

#include "dynamics/simulation_output.hpp"
#include "formats/scenario_file.hpp"
#include "report/simulation_csv.hpp"
#include "report/snapshot_queue.hpp"

namespace vcontact::report {

enum class OutputThread { kOff, kOn };

class AsyncSimulationCsvWriter {
 public:
  /// The memory the queued snapshot copies may take, about: the slots are as many as fit
  /// (snapshotBytes), within [kMinSlots, kMaxSlots]. A slow disk holds the stepping thread back
  /// once every slot waits. Many slots let the writer open its files while the run's first
  /// output times queue (ball_drop's 2 kHz fill 170 slots in the 0.3 ms that takes) and wake
  /// it rarely; the budget keeps a scenario of many pairs to a few dozen slots.
  static constexpr std::size_t kSlotBudgetBytes = std::size_t{4} << 20;  // 4 MiB
  static constexpr std::size_t kMinSlots = 4;
  static constexpr std::size_t kMaxSlots = 1024;

  /// kOn: starts the writer thread, which makes the folder and opens the files
  /// (SimulationCsvWriter's constructor; its errors come at the next write() or commit()),
  /// with `slots` slots (0: from the budget above). kOff: SimulationCsvWriter's constructor
  /// here.
  AsyncSimulationCsvWriter(const std::string& dir, const dynamics::Scenario& scenario,
                           const formats::OutputSelection& outputs, OutputThread thread,
                           std::size_t slots = 0);

  /// Hands the snapshot over (kOn: a copy, written later) or writes it (kOff).
  /// @throws InputError naming the file when a write failed, here or on the writer thread
  ///         since the last call; all temporaries are deleted then
  void write(const dynamics::Snapshot& snapshot);
  /// Waits for the writer thread to write what was handed over, then SimulationCsvWriter::commit.
  /// @throws InputError naming the file when a write, the close or the rename failed; no file
  ///         of the run is left then
  void commit(const std::string& extraPath = "", const std::string& extraText = "");

 private:
  std::optional<SimulationCsvWriter> writer_;  ///< made by the writer thread with kOn
  /// After writer_, so destroyed before it: the thread is joined before the files go.
  std::optional<SnapshotQueue> queue_;
};

/// The bytes of a snapshot of `scenario`, about (its vectors' contents included; a pair's
/// patches counted as its state slots).
std::size_t snapshotBytes(const dynamics::Scenario& scenario);

}  // namespace vcontact::report
