#include "report/async_simulation_csv.hpp"

#include <algorithm>

namespace vcontact::report {

std::size_t snapshotBytes(const dynamics::Scenario& scenario) {
  std::size_t bytes =
      sizeof(dynamics::Snapshot) + scenario.bodies.size() * sizeof(dynamics::BodyKinematics) +
      (scenario.loads.size() + scenario.springs.size()) * sizeof(dynamics::LoadOutput);
  for (const dynamics::ContactPair& pair : scenario.pairs) {
    const std::size_t shares = pair.model.effectIds().size() * sizeof(dynamics::Wrench);
    const std::size_t slots = static_cast<std::size_t>(dynamics::patchSlots(scenario, pair));
    bytes += sizeof(dynamics::PairOutput) + shares;
    if (slots > 1) bytes += slots * (sizeof(dynamics::PatchOutput) + shares);
  }
  return bytes;
}

AsyncSimulationCsvWriter::AsyncSimulationCsvWriter(const std::string& dir,
                                                   const dynamics::Scenario& scenario,
                                                   const formats::OutputSelection& outputs,
                                                   OutputThread thread, std::size_t slots) {
  if (thread == OutputThread::kOff) {
    writer_.emplace(dir, scenario, outputs);
    return;
  }
  if (slots == 0) {
    slots = std::clamp(kSlotBudgetBytes / snapshotBytes(scenario), kMinSlots, kMaxSlots);
  }
  queue_.emplace(
      slots, [this](const dynamics::Snapshot& s) { writer_->write(s); },
      [this, dir, &scenario, outputs] { writer_.emplace(dir, scenario, outputs); });
}

void AsyncSimulationCsvWriter::write(const dynamics::Snapshot& snapshot) {
  if (queue_) {
    queue_->push(snapshot);
  } else {
    writer_->write(snapshot);
  }
}

void AsyncSimulationCsvWriter::commit(const std::string& extraPath, const std::string& extraText) {
  if (queue_) queue_->finish();  // rethrows the writer thread's failure, if any
  writer_->commit(extraPath, extraText);
}

}  // namespace vcontact::report
