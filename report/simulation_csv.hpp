#pragma once
// CSV output of a simulation: bodies.csv (one row per body per output time) and one
// pair_<name>.csv per contact pair (volume, centroid, normal, wrench on the payload at the
// centroid, friction states and, optionally, each effect's share of the wrench), and for a
// pair with several patch state slots pair_<name>_patches.csv (one row per patch per output
// time; dynamics/SCENARIO.md).

#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"

namespace vcontact::report {

class SimulationCsvWriter {
 public:
  /// Creates `dir` if needed and writes the headers. @throws InputError when a file cannot open
  SimulationCsvWriter(const std::string& dir, const dynamics::Scenario& scenario,
                      const formats::OutputSelection& outputs);

  /// Appends one row per body and per pair (buffered; flushed by flush() and on destruction,
  /// so a run that stops with an error keeps its rows).
  void write(const dynamics::Snapshot& snapshot);
  void flush();

  /// The files written, for the summary.
  const std::vector<std::string>& files() const { return files_; }

 private:
  std::ofstream open(const std::string& path);
  void writePatches(double t, const dynamics::PairOutput& p, int state_size, std::ofstream& f);

  const dynamics::Scenario& scenario_;
  formats::OutputSelection outputs_;
  std::ofstream bodies_;
  std::vector<std::ofstream> pairs_;
  std::vector<std::ofstream> patches_;  ///< the pairs' patch files
  std::vector<int> patch_file_;         ///< per pair, its index in patches_, −1 when none
  std::vector<std::string> files_;
};

/// A file-name-safe form of a pair name: letters, digits, '-', '_' kept, others '_'.
std::string fileSafe(const std::string& name);

}  // namespace vcontact::report
