#pragma once
// CSV output of a simulation: bodies.csv (one row per body per output time) and one
// pair_<name>.csv per contact pair (volume, centroid, normal, wrench on the payload at the
// centroid, friction states and, optionally, each effect's share of the wrench), and for a
// pair with several patch state slots pair_<name>_patches.csv (one row per patch per output
// time; docs/SCENARIO.md).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/simulation_output.hpp"
#include "formats/scenario_file.hpp"
#include "io/output_file.hpp"
#include "report/csv_number.hpp"

namespace vcontact::report {

class SimulationCsvWriter {
 public:
  /// Creates `dir` if needed and writes the headers to temporaries beside the final files
  /// (io/output_file.hpp: an io::OutputSet, all files or none). @throws InputError when a
  /// file cannot be created
  SimulationCsvWriter(const std::string& dir, const dynamics::Scenario& scenario,
                      const formats::OutputSelection& outputs);

  /// Appends one row per body and per pair.
  /// @throws InputError naming the file when a write failed (all temporaries are deleted)
  void write(const dynamics::Snapshot& snapshot);
  /// Completes the files: the rows written so far, under their final names, together with
  /// the file `extraPath` holding `extraText` when one is named (the run's summary.json). A
  /// run that stopped with an error commits too, so its output up to the stop is kept. Then the
  /// files an earlier run wrote into the folder and this one did not (removeStaleOutputs) go.
  /// @throws InputError naming the file when a write, the close or the rename failed; no file
  ///         of the run is left then
  void commit(const std::string& extraPath = "", const std::string& extraText = "");

  /// The files written, for the summary.
  const std::vector<std::string>& files() const { return files_; }

 private:
  std::ostream& open(const std::string& path);
  void checkWrites();
  void writeBodies(const dynamics::Snapshot& s);
  void writeLoads(const dynamics::Snapshot& s);
  void writePatches(double t, const dynamics::PairOutput& p, int state_size, std::ostream& f);

  std::string dir_;
  const dynamics::Scenario& scenario_;
  formats::OutputSelection outputs_;
  /// bodies.csv (when selected) first, then each pair's file and its patch file
  io::OutputSet set_;
  std::ostream* bodies_ = nullptr;
  std::vector<std::ostream*> pairs_;
  std::vector<std::ostream*> patches_;  ///< per pair, its patch file; null when it has none
  std::ostream* loads_ = nullptr;       ///< loads.csv, when written
  std::vector<std::string> files_;
  /// One output time's rows of one file, written to it at once; reused from file to file and
  /// from row to row (no allocation per row)
  CsvBuffer text_;
};

/// Rows a run writes: (output times, t = 0 included) × (bodies in bodies.csv + pairs + the
/// patch files' rows, counted as one per state slot: a pair touching in more patches than it
/// has slots writes more, so this is the count of a run whose patches fill their slots + loads
/// and springs in loads.csv).
std::uint64_t outputRowCount(const dynamics::Scenario& scenario,
                             const formats::OutputSelection& outputs);

/// Deletes from `dir` the simulation outputs of an earlier run that are not among `written`
/// (file names): bodies.csv, loads.csv and pair_*.csv whose first line is the header vcontact
/// writes (so that `view` never shows an old pair's forces on new motion, issue 36). Every other
/// file is left alone. Returns the names deleted.
std::vector<std::string> removeStaleOutputs(const std::string& dir,
                                            const std::vector<std::string>& written);

/// The most rows a simulation may write (about 10 GB of CSV at 200 bytes a row): more is
/// refused before the run, with the count, since it would fill a disk rather than be read.
constexpr std::uint64_t kMaxOutputRows = 50'000'000;

}  // namespace vcontact::report
