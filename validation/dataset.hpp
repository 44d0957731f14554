#pragma once
// A rig measurement (docs/DATASET.md): how the payload moved against the plate and
// the wrench that was measured. The reader (formats/dataset_file.hpp) checks the files; this
// layer holds the samples and derives what the file may omit (velocities).
//
// Frames: P is the plate frame, B the payload frame. Each sample holds X_PB (pose of the
// payload in the plate frame), v_PB (velocity of B's origin in P), w_PB (angular velocity
// of B relative to P, in P), and the measured wrench on the payload by the plate: force f_P
// and torque about the payload origin, in P.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "geometry/primitives.hpp"

namespace vcontact::validation {

/// The wrench columns a dataset may hold, in the order of WrenchVector.
inline const std::array<std::string, 6> kWrenchColumns = {"fx", "fy", "fz", "tx", "ty", "tz"};

struct Sample {
  double t = 0.0;  ///< s
  Eigen::Isometry3d X_PB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v_PB = Eigen::Vector3d::Zero();  ///< m/s
  Eigen::Vector3d w_PB = Eigen::Vector3d::Zero();  ///< rad/s
};

struct Dataset {
  std::string name;
  std::string notes;
  std::string sidecarPath;  ///< the .json the user named
  std::string dataPath;     ///< the CSV, resolved
  geometry::Shape payload;
  geometry::Shape plate;
  std::vector<std::string> outputs;     ///< wrench columns to compare, e.g. {"fx", "tz"}
  std::map<std::string, double> noise;  ///< 1-σ per output where the sidecar gives it

  std::vector<Sample> samples;
  /// Every CSV column by name, kinematic, wrench and extra ones alike (never dropped).
  std::map<std::string, Eigen::VectorXd> columns;
  bool velocityFromPositions = false;  ///< vx, vy, vz were absent and were differentiated
  bool omegaFromAttitude = false;      ///< wx, wy, wz were absent and were differentiated

  std::size_t size() const { return samples.size(); }
  /// Measured values of one wrench column; @pre the column exists.
  const Eigen::VectorXd& measured(const std::string& output) const { return columns.at(output); }
};

/// Velocity of the origin by second-order finite differences on a non-uniform grid
/// (one-sided second-order at the ends). @pre at least 3 samples, t strictly increasing.
void differentiatePositions(std::vector<Sample>& samples);

/// Angular velocity from consecutive attitudes: w ≈ log(R_{i+1} R_{i−1}ᵀ)/(t_{i+1} − t_{i−1})
/// at interior samples, one-sided at the ends. Immune to the q/−q sign ambiguity.
void differentiateAttitudes(std::vector<Sample>& samples);

}  // namespace vcontact::validation
