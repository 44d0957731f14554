#pragma once
// Reads a measurement dataset (docs/DATASET.md, format vcontact.dataset/1): the JSON
// sidecar and the CSV it names. Every defect the spec lists stops the read with one
// InputError naming the file, the line and the column where there is one:
//   sidecar not JSON, wrong format, missing or unknown field values, a data file or mesh
//   that does not exist; in the CSV a missing required column, a non-number, NaN or
//   infinity, a row of the wrong width, time not strictly increasing, a quaternion far from
//   unit length, too few samples. Nothing is guessed: velocities are differentiated only
//   when all three columns are absent, and the Dataset says so.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "validation/dataset.hpp"

namespace vcontact::formats {

struct DatasetReadResult {
  validation::Dataset dataset;
  std::vector<std::string> warnings;
};

/// A quaternion written with four or more digits is unit to 1e-3; further off, the column
/// is most likely something else (degrees, a wrong order) and the read stops.
inline constexpr double kDatasetQuaternionTolerance = 1e-3;

/// @param sidecarPath the NAME.json the user named
DatasetReadResult readDataset(const std::string& sidecarPath);

/// A prescribed motion (`vcontact synth --motion`): a CSV with the kinematic columns of a
/// dataset (t, x, y, z, qw, qx, qy, qz; vx, vy, vz and wx, wy, wz optional, each triple
/// differentiated when absent), checked as a dataset's CSV is. Wrench columns are ignored.
/// The result holds the samples and the 14 kinematic columns; nothing else is set.
struct MotionReadResult {
  validation::Dataset dataset;
  std::vector<std::string> warnings;  ///< velocities differentiated
};
MotionReadResult readMotionCsv(const std::string& path);

/// Writes NAME.json and NAME.csv (all columns, 17 significant digits).
/// @param payloadEntry the sidecar's payload entry to write instead of the payload's own
///   (needed for a mesh payload: {"mesh": PATH, "scale": S}); null: the primitive payload
/// @throws InputError when the payload (without payloadEntry) or the plate is a mesh
void writeDataset(const validation::Dataset& dataset, const std::string& sidecarPath,
                  const nlohmann::json* payloadEntry = nullptr);

}  // namespace vcontact::formats
