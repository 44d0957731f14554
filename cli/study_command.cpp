// vcontact study STUDY --out DIR: a study (docs/STUDY.md) is run by the Python package on Dask;
// this command checks the options and hands over to `python3 -m vcontact.study` with the
// package this build made, so that every front end of vcontact is one program.

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>

#include "cli/commands.hpp"

namespace vcontact::cli {
namespace {

struct StudyOptions {
  std::string study;
  std::string out;
  std::optional<int> workers;
  std::string scheduler;
  std::optional<int> chunkSize;
  std::optional<int> run;
  int threads = 0;
  bool h5 = false;
  bool quiet = false;
};

// The Python interpreter and the folder holding the package `vcontact` (the build tree's
// python/), fixed when vcontact was built; VCONTACT_PYTHON and VCONTACT_PYTHON_DIR override.
std::string setting(const char* variable, const char* built) {
  const char* v = std::getenv(variable);
  return v && *v ? v : built;
}

std::vector<std::string> pythonArguments(const StudyOptions& o, const std::string& python) {
  std::vector<std::string> a{python, "-m", "vcontact.study", o.study, "--out", o.out};
  if (o.workers) a.insert(a.end(), {"--workers", std::to_string(*o.workers)});
  if (!o.scheduler.empty()) a.insert(a.end(), {"--scheduler", o.scheduler});
  if (o.chunkSize) a.insert(a.end(), {"--chunk-size", std::to_string(*o.chunkSize)});
  if (o.run) a.insert(a.end(), {"--run", std::to_string(*o.run)});
  if (o.threads) a.insert(a.end(), {"--threads", std::to_string(o.threads)});
  if (o.h5) a.push_back("--h5");
  if (o.quiet) a.push_back("--quiet");
  return a;
}

[[noreturn]] void runStudy(const StudyOptions& o) {
  const std::string python = setting("VCONTACT_PYTHON", VCONTACT_PYTHON_EXECUTABLE);
  const std::string dir = setting("VCONTACT_PYTHON_DIR", VCONTACT_PYTHON_PACKAGE_DIR);
  if (!std::filesystem::exists(std::filesystem::path(dir) / "vcontact" / "study")) {
    throw InputError("study", "the Python package is not in " + dir +
                                  " (this build left it out: it needs pybind11-dev; or set "
                                  "VCONTACT_PYTHON_DIR to the folder holding vcontact/)");
  }
  const char* old = std::getenv("PYTHONPATH");
  const std::string path = old && *old ? dir + ":" + old : dir;
  ::setenv("PYTHONPATH", path.c_str(), 1);
  // A fit study's parts run this program (`vcontact fit --fold`, docs/STUDY.md, "Fit studies").
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) ::setenv("VCONTACT_BINARY", self.c_str(), 0);
  // A sanitizer build: the interpreter loads the ASan and C++ runtimes first, for the
  // instrumented module, and CPython's objects alive at exit are no leaks (CMakeLists.txt,
  // VCONTACT_INTERPRETER_PRELOAD). Empty in every other build.
  if (const std::string preload = VCONTACT_PYTHON_PRELOAD; !preload.empty()) {
    ::setenv("LD_PRELOAD", preload.c_str(), 1);
    ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
  }
  std::vector<std::string> args = pythonArguments(o, python);
  std::vector<char*> argv;
  for (std::string& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  ::execvp(python.c_str(), argv.data());
  throw InputError("study", "cannot start " + python + ": " + std::strerror(errno));
}

}  // namespace

void addStudyCommand(CLI::App& app) {
  auto opts = std::make_shared<StudyOptions>();
  CLI::App* cmd = app.add_subcommand(
      "study",
      "Run a study (docs/STUDY.md): a scenario many times with parameters varied by grid, list "
      "or a seeded Sobol/Halton sample of distributions, in chunks on Dask (a local cluster, or "
      "a running scheduler); results.csv (and results.h5), report.html. Rerun to resume. A "
      "study with \"fit\": the k+1 parts of a cross-validated trajectory fit on Dask, merged "
      "into fit/ as `vcontact fit` writes it.");
  cmd->add_option("STUDY", opts->study, "study JSON file (vcontact.study/1)")->required();
  cmd->add_option("--out", opts->out, "output folder; rerunning into it resumes")->required();
  cmd->add_option("--workers", opts->workers,
                  "local Dask worker processes (default: one per core); 0: no Dask, the runs in "
                  "this process on --threads threads")
      ->check(CLI::Range(0, 4096));
  cmd->add_option("--scheduler", opts->scheduler,
                  "a running Dask scheduler, tcp://HOST:PORT (its workers must see the study's "
                  "files at the same paths and import vcontact)");
  cmd->add_option("--chunk-size", opts->chunkSize,
                  "runs per Dask task (default: the study's chunk_size, else runs/100, at most "
                  "1000)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--threads", opts->threads, "with --workers 0: threads (0: every core)")
      ->check(CLI::Range(0, 4096));
  cmd->add_option("--run", opts->run,
                  "run only this run (0-based), alone, writing what `simulate` writes to --out")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--h5", opts->h5, "also write results.h5 (written anyway from 10000 runs)");
  cmd->add_flag("--quiet", opts->quiet, "no progress on standard error (none in pipes or CI)");
  cmd->callback([opts] { runStudy(*opts); });
}

}  // namespace vcontact::cli
