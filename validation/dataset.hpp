#pragma once
// A rig measurement (docs/DATASET.md): how the payload moved against the plate and
// the wrench that was measured. The reader (formats/dataset_file.hpp) checks the files; this
// layer holds the samples and derives what the file may omit (velocities).
//
// Bodies and frames (MODEL.md): body A is the payload, body B the plate; A and B also name
// their frames. Each sample holds X_BA (pose of the payload in the plate frame), v_BA
// (velocity of A's origin in B), w_BA (angular velocity of A relative to B, in B), and the
// measured wrench on the payload by the plate: force f_B and torque about the payload
// origin, in B.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/primitives.hpp"

namespace vcontact::volume {
struct RecoveredSurface;  // opaque: volume/contact.hpp makes and describes it
}

namespace vcontact::validation {

/// The wrench columns a dataset may hold, in the order of WrenchVector.
inline const std::array<std::string, 6> kWrenchColumns = {"fx", "fy", "fz", "tx", "ty", "tz"};

/// The outputs of a dynamic dataset (docs/DATASET.md, "Dynamic datasets"): the payload's
/// recorded position (m) and attitude (rad), set against the simulated ones.
inline const std::array<std::string, 2> kTrajectoryOutputs = {"position", "attitude"};

/// "kinematic": the record dictates the payload's path and the wrench is compared;
/// "dynamic": the payload is free from a recorded initial state and its path is compared.
enum class DatasetMode { kKinematic, kDynamic };

struct Sample {
  double t = 0.0;  ///< s
  Eigen::Isometry3d X_BA = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v_BA = Eigen::Vector3d::Zero();  ///< m/s
  Eigen::Vector3d w_BA = Eigen::Vector3d::Zero();  ///< rad/s
};

/// The payload's mass properties, where the sidecar gives them (`payload_inertia`,
/// docs/DATASET.md): what the payload's own inertia adds to a measured wrench (rig.hpp).
struct PayloadInertia {
  double mass = 0.0;  ///< kg
  /// Inertia tensor about the centre of mass, in the payload frame, kg·m².
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  Eigen::Vector3d com = Eigen::Vector3d::Zero();  ///< centre of mass in the payload frame, m
};

struct Dataset {
  DatasetMode mode = DatasetMode::kKinematic;
  std::string name;
  std::string notes;
  std::string sidecarPath;  ///< the .json the user named
  std::string dataPath;     ///< the CSV, resolved
  geometry::Shape payload;
  geometry::Shape plate;
  /// A mesh payload's recovered surface (the payload's "surface": "recovered",
  /// docs/DATASET.md): its contact with a half-space plate is then that of the true sphere or
  /// capped cylinder where one applies. Null: the polyhedron.
  std::shared_ptr<const volume::RecoveredSurface> payload_surface;
  std::vector<std::string> outputs;       ///< wrench columns to compare, e.g. {"fx", "tz"}
  std::map<std::string, double> noise;    ///< 1-σ per output where the sidecar gives it
  std::optional<PayloadInertia> inertia;  ///< where the sidecar gives it (dynamic: always)
  /// Dynamic datasets: the pose of the plate's shape in the plate frame ("plate_pose"; the
  /// identity by default) and gravity in the plate frame ("gravity", m/s²).
  Eigen::Isometry3d X_BP = Eigen::Isometry3d::Identity();
  Eigen::Vector3d gravity_B = Eigen::Vector3d(0.0, 0.0, -9.81);

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
