// report::AsyncSimulationCsvWriter: a failed write on the writer thread reaches the caller as
// the synchronous writer's error and leaves no file; a run abandoned by an exception joins the
// thread and leaves no file either. (The files themselves, byte for byte against the
// synchronous writer, are compared through the CLI: tests/cli/output_thread_test.cpp.)

#include "report/async_simulation_csv.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"
#include "geometry/error.hpp"
#include "support/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using vcontact::InputError;
using vcontact::report::AsyncSimulationCsvWriter;
using vcontact::report::OutputThread;
using vcontact::test::ScratchDir;

const std::string kBallDrop = std::string(VCONTACT_ASSETS_DIR) + "/scenarios/ball_drop.json";

// The names under `dir`, links not followed.
std::vector<std::string> namesUnder(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    names.push_back(e.path().lexically_relative(dir).string());
  std::sort(names.begin(), names.end());
  return names;
}

// Runs the ball drop (601 output times, ~150 kB of bodies.csv) into `out` and commits; returns
// the message of the InputError the writer threw on the way, empty when none.
std::string runBallDrop(const fs::path& out, OutputThread thread) {
  const vcontact::formats::ScenarioFile file = vcontact::formats::readScenarioFile(kBallDrop);
  vcontact::dynamics::Simulator sim(file.scenario);
  try {
    AsyncSimulationCsvWriter writer(out.string(), sim.scenario(), file.outputs, thread);
    vcontact::dynamics::SimulationSummary summary;
    sim.run([&](const vcontact::dynamics::Snapshot& s) { writer.write(s); }, [](double) {},
            summary);
    writer.commit();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// bodies.csv is a link to /dev/full: it is written in place (io::OutputFile), its header fits
// the stream's buffer, and the first flush of rows fails with ENOSPC, on the writer thread
// when there is one. Both writers must say the same and leave only the link.
TEST(AsyncSimulationCsv, AWriteFailureOnTheWriterThreadReadsAsTheSynchronousOne) {
  const ScratchDir scratch{"async_csv_full"};
  std::vector<std::string> messages;
  for (const OutputThread thread : {OutputThread::kOff, OutputThread::kOn}) {
    scratch.reset();
    const fs::path out = scratch / "out";
    fs::create_directories(out);
    fs::create_symlink("/dev/full", out / "bodies.csv");
    messages.push_back(runBallDrop(out, thread));
    EXPECT_EQ(namesUnder(out), std::vector<std::string>{"bodies.csv"});
  }
  const std::string expected =
      (scratch / "out" / "bodies.csv").string() + ": write failed (No space left on device)";
  EXPECT_EQ(messages[0], expected);
  EXPECT_EQ(messages[1], expected);
}

// A run ended by an exception of the caller's (here after every snapshot was handed over,
// before the commit): the destructor joins the writer thread and deletes the temporaries and
// the folders the writer made.
TEST(AsyncSimulationCsv, AnAbandonedRunLeavesNoFile) {
  const ScratchDir scratch{"async_csv_abandoned"};
  const fs::path out = scratch / "new" / "out";
  const vcontact::formats::ScenarioFile file = vcontact::formats::readScenarioFile(kBallDrop);
  vcontact::dynamics::Simulator sim(file.scenario);
  int handed = 0;
  try {
    AsyncSimulationCsvWriter writer(out.string(), sim.scenario(), file.outputs, OutputThread::kOn);
    vcontact::dynamics::SimulationSummary summary;
    sim.run(
        [&](const vcontact::dynamics::Snapshot& s) {
          writer.write(s);
          ++handed;
        },
        [](double) {}, summary);
    throw std::runtime_error("interrupted");
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "interrupted");
  }
  EXPECT_EQ(handed, 601);  // 0.3 s at 2 kHz, t = 0 included
  EXPECT_EQ(namesUnder(scratch.path()), std::vector<std::string>{});
}

// The slots follow the memory budget: the ball drop's small snapshots take the most slots, and
// bin_of_ten's 55 pairs with patches fewer, none beyond the budget.
TEST(AsyncSimulationCsv, TheSlotsFitTheMemoryBudget) {
  using W = AsyncSimulationCsvWriter;
  const auto bytes = [](const std::string& name) {
    const std::string path = std::string(VCONTACT_ASSETS_DIR) + "/scenarios/" + name + ".json";
    return vcontact::report::snapshotBytes(vcontact::formats::readScenarioFile(path).scenario);
  };
  const std::size_t ball = bytes("ball_drop"), bin = bytes("bin_of_ten");
  EXPECT_LT(ball * W::kMaxSlots, W::kSlotBudgetBytes);  // ball_drop: the cap of 1024 slots
  EXPECT_GT(bin, 50 * ball);  // 55 pairs (each with patch slots) against one
  EXPECT_GE(W::kSlotBudgetBytes / bin, W::kMinSlots);
  EXPECT_LT(W::kSlotBudgetBytes / bin, W::kMaxSlots);
}

}  // namespace
