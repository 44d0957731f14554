#pragma once
// Conversions shared by the binding files: poses from NumPy or text, ContactVolume to a dict,
// JSON to and from Python objects (through the json module, so that a dict round-trips).

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include "geometry/primitives.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::python {

namespace py = pybind11;

/// A pose given as a 4×4 array, a (p, quaternion (w, x, y, z)) pair, a 3-vector (translation)
/// or the command line's text ("x,y,z[,roll,pitch,yaw | ,qw,qx,qy,qz]").
/// @throws InputError naming `what` when it is none of these or not a rigid transform
Eigen::Isometry3d toPose(const py::handle& pose, const std::string& what);

/// The 4×4 homogeneous matrix of a pose.
Eigen::Matrix4d poseMatrix(const Eigen::Isometry3d& X);

/// Every ContactVolume field by the names of `vcontact volume --json` (README "Output").
py::dict contactVolumeDict(const volume::ContactVolume& cv);

/// The inverse of contactVolumeDict, for Model.wrench.
/// @throws InputError naming the missing key
volume::ContactVolume contactVolumeFrom(const py::dict& d);

/// A JSON value as the Python object json.loads would give, and back.
py::object toPython(const nlohmann::json& j);
nlohmann::json toJson(const py::handle& o);

/// A shape plus what reading it reported (mesh repairs, precision).
struct PyShape {
  geometry::Shape shape;
  std::vector<std::string> warnings;
};

}  // namespace vcontact::python
