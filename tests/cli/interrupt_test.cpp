// An interrupted `vcontact simulate` (issue 36): SIGINT or SIGTERM ends the run as a stopped
// one (exit 3, the rows so far under their names, summary.json saying "interrupted", a message
// on standard error) instead of leaving hidden temporaries and no word; a run killed outright
// leaves temporaries that the next run into the folder cleans. Real signals, sent to a child
// process running the real program.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "support/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using vcontact::test::readAll;
using vcontact::test::ScratchDir;

// A ball resting on a plate for 1000 simulated seconds: minutes of stepping, far longer than
// the test waits before it signals.
std::string longScenario() {
  return R"({"format": "vcontact.scenario/1", "duration": 1000, "output_rate": 100,
    "gravity": [0, 0, -9.81],
    "bodies": [{"name": "plate", "shape": "halfspace", "motion": "fixed"},
               {"name": "ball", "shape": "sphere:0.01", "density": 7900, "pose": "0,0,0.012"}],
    "pairs": [{"a": "ball", "b": "plate", "method": "analytic",
               "model": {"format": "vcontact.model/1",
                         "effects": {"stiffness": {"kv": 1e12}, "damping": {"a": 100}}}}]})";
}

// `vcontact simulate SCENARIO --out OUT` in a child process, its standard error into `err`.
pid_t startSimulation(const fs::path& scenario, const fs::path& out, const fs::path& err) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 2);
    ::execl(VCONTACT_BINARY, VCONTACT_BINARY, "simulate", scenario.c_str(), "--out", out.c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

// Whether `dir` holds a hidden temporary of the run: the run is stepping then.
bool hasTemporary(const fs::path& dir) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().filename().string().find(".tmp-") != std::string::npos) return true;
  }
  return false;
}

// Waits (up to a minute: a loaded machine) for the run to have begun stepping.
bool waitForRun(const fs::path& out) {
  for (int i = 0; i < 600; ++i) {
    if (hasTemporary(out)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

int exitStatus(pid_t pid, bool& signalled) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  signalled = WIFSIGNALED(status);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

void expectInterruptedLikeAStop(int signal, const std::string& name) {
  const ScratchDir scratch{"interrupt_" + name};
  std::ofstream(scratch / "long.json") << longScenario();
  const fs::path out = scratch / "out";
  const pid_t pid = startSimulation(scratch / "long.json", out, scratch / "err.txt");
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(waitForRun(out)) << readAll(scratch / "err.txt");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // some rows written
  ::kill(pid, signal);
  bool signalled = false;
  EXPECT_EQ(exitStatus(pid, signalled), 3) << readAll(scratch / "err.txt");
  EXPECT_FALSE(signalled);
  const std::string err = readAll(scratch / "err.txt");
  EXPECT_NE(err.find("simulation stopped: interrupted by " + name + " at t = "), std::string::npos)
      << err;
  EXPECT_NE(err.find("output up to then is in " + out.string()), std::string::npos) << err;
  EXPECT_FALSE(hasTemporary(out));
  const nlohmann::json summary = nlohmann::json::parse(readAll(out / "summary.json"));
  EXPECT_EQ(summary.at("stop_cause"), "interrupted");
  const double stopped = summary.at("stopped_at_s").get<double>();
  EXPECT_GT(stopped, 0.0);
  EXPECT_LT(stopped, 1000.0);
  // the rows up to the stop: a header, t = 0 and every 10 ms output time up to it
  const std::string bodies = readAll(out / "bodies.csv");
  const long rows = static_cast<long>(std::count(bodies.begin(), bodies.end(), '\n')) - 1;
  EXPECT_GE(rows, 2 * 1);  // two bodies at t = 0 at least
  EXPECT_TRUE(fs::exists(out / "pair_ball-plate.csv"));
}

TEST(Interrupt, SigintEndsTheRunAsAStoppedOne) { expectInterruptedLikeAStop(SIGINT, "SIGINT"); }

TEST(Interrupt, SigtermEndsTheRunAsAStoppedOne) { expectInterruptedLikeAStop(SIGTERM, "SIGTERM"); }

// SIGKILL cannot be caught: the temporaries stay, and the next run into the folder removes
// them (their process no longer runs) and writes its own files.
TEST(Interrupt, TemporariesOfAKilledRunAreCleanedByTheNextRun) {
  const ScratchDir scratch{"interrupt_kill"};
  std::ofstream(scratch / "long.json") << longScenario();
  const fs::path out = scratch / "out";
  const pid_t pid = startSimulation(scratch / "long.json", out, scratch / "err.txt");
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(waitForRun(out)) << readAll(scratch / "err.txt");
  ::kill(pid, SIGKILL);
  bool signalled = false;
  EXPECT_EQ(exitStatus(pid, signalled), -SIGKILL);
  ASSERT_TRUE(hasTemporary(out));
  nlohmann::json shortRun = nlohmann::json::parse(longScenario());
  shortRun["duration"] = 0.01;
  std::ofstream(scratch / "short.json") << shortRun.dump();
  const pid_t next = startSimulation(scratch / "short.json", out, scratch / "err2.txt");
  EXPECT_EQ(exitStatus(next, signalled), 0) << readAll(scratch / "err2.txt");
  EXPECT_FALSE(hasTemporary(out));
  EXPECT_TRUE(fs::exists(out / "summary.json"));
}

}  // namespace
