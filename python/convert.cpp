#include "python/convert.hpp"

#include <cmath>
#include <limits>

#include "geometry/error.hpp"
#include "io/json_file.hpp"
#include "io/shape_spec.hpp"

namespace vcontact::python {
namespace {

// A 4×4 pose's rotation block must be orthonormal with determinant +1 to this tolerance: the
// same bound the text form puts on a quaternion's norm (io/shape_spec.hpp).
constexpr double kRotationTolerance = 1e-6;

// Every value of `a` finite, or a ValueError naming `what` (a NaN position gave volume 0).
void checkFinite(const double* values, py::ssize_t n, const std::string& what) {
  for (py::ssize_t i = 0; i < n; ++i) {
    if (!std::isfinite(values[i])) {
      throw InputError(what, "expected finite numbers, got " + std::to_string(values[i]));
    }
  }
}

Eigen::Vector3d vector3(const py::handle& o, const std::string& what) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(o);
  if (!a || a.size() != 3) throw InputError(what, "expected 3 numbers");
  checkFinite(a.data(), 3, what);
  return {a.data()[0], a.data()[1], a.data()[2]};
}

// A number of a contact dict: a TypeError when it is not one (pybind's cast error would be a
// RuntimeError), a ValueError when it is not finite (a NaN volume gave a zero wrench).
double contactNumber(const py::handle& o, const std::string& key) {
  const std::string what = "contact['" + key + "']";
  if (!py::isinstance<py::float_>(o) && !py::isinstance<py::int_>(o) &&
      !py::isinstance(o, py::module_::import("numbers").attr("Real"))) {
    throw py::type_error(what + ": expected a number, got " +
                         std::string(py::str(py::type::of(o).attr("__name__"))));
  }
  const double x = o.cast<double>();
  checkFinite(&x, 1, what);
  return x;
}

Eigen::Matrix3d contactMatrix(const py::handle& o, const std::string& key) {
  const std::string what = "contact['" + key + "']";
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(o);
  if (!a || a.ndim() != 2 || a.shape(0) != 3 || a.shape(1) != 3) {
    throw py::type_error(what + ": expected a 3x3 array of numbers");
  }
  checkFinite(a.data(), 9, what);
  Eigen::Matrix3d M;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) M(i, j) = a.at(i, j);
  return M;
}

}  // namespace

Eigen::Isometry3d toPose(const py::handle& pose, const std::string& what) {
  if (pose.is_none()) return Eigen::Isometry3d::Identity();
  if (py::isinstance<py::str>(pose)) return io::parsePose(pose.cast<std::string>(), what);
  if (py::isinstance<py::tuple>(pose) || py::isinstance<py::list>(pose)) {
    const auto seq = py::reinterpret_borrow<py::sequence>(pose);
    if (seq.size() == 2) {
      const auto q = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(
          py::object(seq[1]));
      if (!q || q.size() != 4) throw InputError(what, "expected (p, (qw, qx, qy, qz))");
      checkFinite(q.data(), 4, what);
      return io::poseFromQuaternion(vector3(py::object(seq[0]), what),
                                    {q.data()[0], q.data()[1], q.data()[2], q.data()[3]}, what);
    }
  }
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(pose);
  if (a && a.size() == 3) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = vector3(pose, what);
    return X;
  }
  if (!a || a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4) {
    throw InputError(what, "expected a 4x4 array, (p, quaternion wxyz), a 3-vector or pose text");
  }
  Eigen::Matrix4d M;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) M(i, j) = a.at(i, j);
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  const double offOrthonormal =
      (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!M.allFinite() || offOrthonormal > kRotationTolerance || R.determinant() < 0.0 ||
      M.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) {
    throw InputError(what,
                     "the 4x4 array is not a rigid transform (rotation block orthonormal "
                     "to 1e-6 with determinant +1, last row 0 0 0 1)");
  }
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(R).normalized().toRotationMatrix();
  X.translation() = M.topRightCorner<3, 1>();
  return X;
}

Eigen::Matrix4d poseMatrix(const Eigen::Isometry3d& X) { return X.matrix(); }

py::dict contactVolumeDict(const volume::ContactVolume& cv) {
  py::dict d;
  d["in_contact"] = cv.inContact();
  d["volume"] = cv.volume;
  d["centroid"] = Eigen::Vector3d(cv.p_WC);
  d["normal"] = Eigen::Vector3d(cv.n_W);
  // NaN only where the query left the depth out (QueryOptions::depth): not computed, so None
  d["depth"] = std::isnan(cv.depth) ? py::object(py::none()) : py::float_(cv.depth);
  d["area"] = cv.area;
  d["r_gyr"] = cv.r_gyr;
  d["J_v"] = Eigen::Matrix3d(cv.J_v);
  d["J_s"] = Eigen::Matrix3d(cv.J_s);
  d["relative_error"] =
      std::isnan(cv.relative_error) ? py::object(py::none()) : py::float_(cv.relative_error);
  d["method"] = volume::methodName(cv.method);
  return d;
}

volume::ContactVolume contactVolumeFrom(const py::dict& d) {
  const auto get = [&](const char* key) -> py::handle {
    if (!d.contains(key)) {
      throw InputError("contact", std::string("no key '") + key +
                                      "' (pass a patch or the aggregate that contact() returns)");
    }
    return d[key];
  };
  volume::ContactVolume cv;
  cv.volume = contactNumber(get("volume"), "volume");
  cv.p_WC = vector3(get("centroid"), "contact['centroid']");
  cv.n_W = vector3(get("normal"), "contact['normal']");
  // None: the depth was not asked for (contact(depth=False)); the model does not read it
  cv.depth = get("depth").is_none() ? std::numeric_limits<double>::quiet_NaN()
                                    : contactNumber(get("depth"), "depth");
  cv.area = contactNumber(get("area"), "area");
  cv.r_gyr = contactNumber(get("r_gyr"), "r_gyr");
  cv.J_v = contactMatrix(get("J_v"), "J_v");
  cv.J_s = contactMatrix(get("J_s"), "J_s");
  if (!py::isinstance<py::str>(get("method")))
    throw py::type_error("contact['method']: expected a string such as 'exact'");
  cv.method = volume::parseMethod(get("method").cast<std::string>());
  if (!(std::abs(cv.n_W.norm() - 1.0) < kRotationTolerance)) {
    throw InputError("contact.normal", "expected a unit vector");
  }
  return cv;
}

py::object toPython(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

nlohmann::json toJson(const py::handle& o) {
  // Strictly, as a file: {1: 0, "1": 0} dumps to a repeated key.
  return io::parseJsonText(py::module_::import("json").attr("dumps")(o).cast<std::string>(),
                           "dict");
}

}  // namespace vcontact::python
