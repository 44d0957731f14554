// diagnose_binary/<which>: `vcontact diagnose` run as a user runs it, by this build's binary
// and by a reference binary (VCONTACT_REFERENCE_BINARY, e.g. main's build) back to back in the
// same run, on one record (VCONTACT_DIAGNOSE_RECORD, a dataset sidecar, and
// VCONTACT_DIAGNOSE_MODEL, the start model; VCONTACT_DIAGNOSE_ARGS adds options such as
// --candidates FILE). Issue 37 item 6: a 6,400-sample record with 9 candidates in ≤ 10 s
// wall. Reports wall time and the children's CPU time (user + system, getrusage) per run,
// and the verdict line each printed, so that a speed-up that changes the verdict shows.
// Skipped (with a message) when the variables are not set.

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

double childrenCpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Runs the command; returns its first line starting with "  verdict:" (the first stage's).
std::string runForVerdict(const std::string& command) {
  std::string verdict;
  FILE* p = popen(command.c_str(), "r");
  if (!p) return "(could not run)";
  std::array<char, 4096> line{};
  while (std::fgets(line.data(), static_cast<int>(line.size()), p)) {
    const std::string s(line.data());
    if (verdict.empty() && s.rfind("  verdict:", 0) == 0)
      verdict = s.substr(11, s.find(" (time") - 11);
  }
  pclose(p);
  return verdict;
}

void BM_DiagnoseBinary(benchmark::State& state, const char* binaryVariable) {
  const char* binary = std::getenv(binaryVariable);
  const char* record = std::getenv("VCONTACT_DIAGNOSE_RECORD");
  const char* model = std::getenv("VCONTACT_DIAGNOSE_MODEL");
  const char* extra = std::getenv("VCONTACT_DIAGNOSE_ARGS");
  if (!binary || !record || !model) {
    state.SkipWithError(
        "set VCONTACT_REFERENCE_BINARY, VCONTACT_THIS_BINARY, VCONTACT_DIAGNOSE_RECORD and "
        "VCONTACT_DIAGNOSE_MODEL");
    return;
  }
  const std::string out = std::string("/tmp/diagnose_binary_bench_") + binaryVariable;
  const std::string command = std::string(binary) + " diagnose " + record + " --model " + model +
                              (extra ? std::string(" ") + extra : "") + " --out " + out +
                              " 2>/dev/null";
  std::string verdict;
  double cpu = 0.0;
  for (auto _ : state) {
    std::system(("rm -rf " + out).c_str());
    const double before = childrenCpuSeconds();
    verdict = runForVerdict(command);
    cpu += childrenCpuSeconds() - before;
  }
  state.counters["cpu_s"] = benchmark::Counter(cpu, benchmark::Counter::kAvgIterations);
  state.SetLabel("verdict " + verdict);
}

BENCHMARK_CAPTURE(BM_DiagnoseBinary, reference, "VCONTACT_REFERENCE_BINARY")
    ->Name("diagnose_binary/reference")
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_DiagnoseBinary, this_build, "VCONTACT_THIS_BINARY")
    ->Name("diagnose_binary/this_build")
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
