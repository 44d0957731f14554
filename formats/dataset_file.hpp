#pragma once
// Reads a measurement dataset (docs/DATASET.md, format vcontact.dataset/1): the JSON
// sidecar and the CSV it names. Every defect the spec lists stops the read with one
// InputError naming the file, the line and the column where there is one:
//   sidecar not JSON, wrong format, missing or unknown field values, a data file or mesh
//   that does not exist; in the CSV a missing required column, a non-number, NaN or
//   infinity, a row of the wrong width, time not strictly increasing, a quaternion far from
//   unit length, too few samples. Nothing is guessed: velocities are differentiated only
//   when all three columns are absent, and the Dataset says so.

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

/// Writes NAME.json and NAME.csv (all columns, 17 significant digits).
/// @throws InputError when the payload or plate is a mesh (only primitives are written)
void writeDataset(const validation::Dataset& dataset, const std::string& sidecarPath);

}  // namespace vcontact::formats
