// The recognised surfaces' geometry: distance and normal of each kind, and the least-squares
// polish of a surface's parameters to the vertices it covers (Ceres).

#include <ceres/ceres.h>

#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

#include "geometry/surface_recognition_internal.hpp"

namespace vcontact::geometry {
namespace {

constexpr int kParameters = 8;  // the most a kind needs (a torus)

// Distance of p to a surface given by the raw parameters q (layout in pack()), positive
// away from the plane's normal, the sphere's centre, the axis, the cone's inside or the
// tube's centre line. Written once for doubles and for Ceres' jets.
template <class T>
T rawDistance(SurfaceKind kind, const T* q, const Eigen::Vector3d& p) {
  using std::sqrt;
  const T w[3] = {T(p.x()) - q[0], T(p.y()) - q[1], T(p.z()) - q[2]};
  if (kind == SurfaceKind::kPlane) {  // q = (n, d): (n·p − d)/|n|
    const T n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
    return (q[0] * T(p.x()) + q[1] * T(p.y()) + q[2] * T(p.z()) - q[3]) / sqrt(n2);
  }
  const T ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  if (kind == SurfaceKind::kSphere) return sqrt(ww) - q[3];
  const T uu = q[3] * q[3] + q[4] * q[4] + q[5] * q[5];
  const T h = (w[0] * q[3] + w[1] * q[4] + w[2] * q[5]) / sqrt(uu);  // along the axis
  // Distance from the axis; a point on the axis has no radial direction, and the floor keeps
  // the derivative finite there (it is far from any surface that passes the tolerance).
  const T rho = sqrt(std::max(ww - h * h, T(1e-300)));
  if (kind == SurfaceKind::kCylinder) return rho - q[6];
  if (kind == SurfaceKind::kCone) return rho * cos(q[6]) - h * sin(q[6]);
  return sqrt((rho - q[6]) * (rho - q[6]) + h * h) - q[7];  // torus
}

std::array<double, kParameters> pack(const RecognisedSurface& s) {
  std::array<double, kParameters> q{};
  const Eigen::Vector3d& c = s.point;
  const Eigen::Vector3d& u = s.axis;
  if (s.kind == SurfaceKind::kPlane) return {u.x(), u.y(), u.z(), u.dot(c), 0, 0, 0, 0};
  q = {c.x(), c.y(), c.z(), u.x(), u.y(), u.z(), 0.0, 0.0};
  if (s.kind == SurfaceKind::kSphere) q[3] = s.radius;
  if (s.kind == SurfaceKind::kCylinder) q[6] = s.radius;
  if (s.kind == SurfaceKind::kCone) q[6] = s.angle;
  if (s.kind == SurfaceKind::kTorus) q[6] = s.radius, q[7] = s.minor_radius;
  return q;
}

RecognisedSurface unpack(RecognisedSurface s, const std::array<double, kParameters>& q) {
  if (s.kind == SurfaceKind::kPlane) {
    const Eigen::Vector3d n(q[0], q[1], q[2]);
    s.axis = n.normalized();
    s.point -= s.axis * (s.axis.dot(s.point) - q[3] / n.norm());  // onto the plane
    return s;
  }
  s.point = {q[0], q[1], q[2]};
  if (s.kind == SurfaceKind::kSphere) {
    s.radius = q[3];
    return s;
  }
  s.axis = Eigen::Vector3d(q[3], q[4], q[5]).normalized();
  if (s.kind == SurfaceKind::kCylinder) s.radius = q[6];
  if (s.kind == SurfaceKind::kCone) s.angle = q[6];
  if (s.kind == SurfaceKind::kTorus) s.radius = q[6], s.minor_radius = q[7];
  return s;
}

// The parameters a kind does not use, held constant.
std::vector<int> unusedParameters(SurfaceKind kind) {
  switch (kind) {
    case SurfaceKind::kPlane:
    case SurfaceKind::kSphere:
      return {4, 5, 6, 7};
    case SurfaceKind::kCylinder:
    case SurfaceKind::kCone:
      return {7};
    case SurfaceKind::kTorus:
      return {};
  }
  return {};
}

struct DistanceResidual {
  SurfaceKind kind;
  Eigen::Vector3d p;
  template <class T>
  bool operator()(const T* q, T* residual) const {
    residual[0] = rawDistance(kind, q, p);
    return true;
  }
};

// The surface moved by `shift` and scaled by `scale` (positions, radii; angles kept).
RecognisedSurface similar(RecognisedSurface s, const Eigen::Vector3d& shift, double scale) {
  s.point = (s.point + shift) * scale;
  s.radius *= scale;
  s.minor_radius *= scale;
  return s;
}

// True when the points fix the surface: the fit's Jacobian has full rank but for the kind's
// gauge freedoms (a plane's normal and an axis direction are free in length, a cylinder's
// axis point slides along it). Points on two circles fix one cone but a whole family of tori,
// so a frustum is a cone, not some torus through its rims.
bool determined(ceres::Problem& problem, SurfaceKind kind) {
  ceres::CRSMatrix crs;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, nullptr, nullptr, &crs);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r)
    for (int k = crs.rows[r]; k < crs.rows[r + 1]; ++k) J(r, crs.cols[k]) = crs.values[k];
  const Eigen::VectorXd sigma =
      Eigen::JacobiSVD<Eigen::MatrixXd>(J.transpose() * J).singularValues();
  constexpr double kRankTolerance = 1e-12;  // of the largest, on JᵀJ (squares of J's: 1e-6)
  const int rank = static_cast<int>((sigma.array() > kRankTolerance * sigma(0)).count());
  int gauge = 0;
  if (kind == SurfaceKind::kPlane || kind == SurfaceKind::kCone || kind == SurfaceKind::kTorus)
    gauge = 1;
  if (kind == SurfaceKind::kCylinder) gauge = 2;
  return sigma.size() > 0 && rank >= crs.num_cols - gauge;
}

}  // namespace

const char* surfaceKindName(SurfaceKind kind) {
  switch (kind) {
    case SurfaceKind::kPlane:
      return "plane";
    case SurfaceKind::kSphere:
      return "sphere";
    case SurfaceKind::kCylinder:
      return "cylinder";
    case SurfaceKind::kCone:
      return "cone";
    case SurfaceKind::kTorus:
      return "torus";
  }
  return "?";
}

double signedDistance(const RecognisedSurface& s, const Eigen::Vector3d& p) {
  const std::array<double, kParameters> q = pack(s);
  const double d = rawDistance(s.kind, q.data(), p);
  return s.convex ? d : -d;
}

Eigen::Vector3d outwardNormal(const RecognisedSurface& s, const Eigen::Vector3d& p) {
  if (s.kind == SurfaceKind::kPlane) return s.axis;
  const Eigen::Vector3d w = p - s.point;
  Eigen::Vector3d n;
  if (s.kind == SurfaceKind::kSphere) {
    n = w.norm() > 0.0 ? w.normalized() : Eigen::Vector3d::UnitZ();
  } else {
    const Eigen::Vector3d radial = w - s.axis * s.axis.dot(w);
    const Eigen::Vector3d e = radial.norm() > 0.0 ? radial.normalized() : s.axis.unitOrthogonal();
    if (s.kind == SurfaceKind::kCylinder) n = e;
    if (s.kind == SurfaceKind::kCone) n = e * std::cos(s.angle) - s.axis * std::sin(s.angle);
    if (s.kind == SurfaceKind::kTorus) {
      const Eigen::Vector3d tube = p - (s.point + s.radius * e);
      n = tube.norm() > 0.0 ? tube.normalized() : e;
    }
  }
  return s.convex ? n : -n;
}

std::string describe(const RecognisedSurface& s) {
  std::ostringstream o;
  o << std::setprecision(9);
  const auto vec = [&](const Eigen::Vector3d& v) {
    o << '(' << v.x() << ", " << v.y() << ", " << v.z() << ')';
  };
  o << surfaceKindName(s.kind) << (s.convex ? "" : " (concave)") << ": ";
  switch (s.kind) {
    case SurfaceKind::kPlane:
      o << "point ", vec(s.point), o << " m, normal ", vec(s.axis);
      break;
    case SurfaceKind::kSphere:
      o << "centre ", vec(s.point), o << " m, radius " << s.radius << " m";
      break;
    case SurfaceKind::kCylinder:
      o << "axis through ", vec(s.point), o << " m along ", vec(s.axis);
      o << ", radius " << s.radius << " m";
      break;
    case SurfaceKind::kCone:
      o << "apex ", vec(s.point), o << " m, axis ", vec(s.axis);
      o << ", half-angle " << s.angle * 180.0 / M_PI << " deg";
      break;
    case SurfaceKind::kTorus:
      o << "centre ", vec(s.point), o << " m, axis ", vec(s.axis);
      o << ", radii " << s.radius << " m and " << s.minor_radius << " m";
      break;
  }
  o << std::setprecision(4) << "; " << s.faces.size() << " faces, area " << s.area
    << " m^2, residual rms " << s.rms_residual << " m, max " << s.max_residual << " m";
  return o.str();
}

namespace detail {

std::optional<RecognisedSurface> polishSurface(const RecognisedSurface& start,
                                               const std::vector<Eigen::Vector3d>& points) {
  if (points.empty()) return std::nullopt;
  // In coordinates centred on the points and scaled to their spread, so the parameters are of
  // order one and the solver's tolerances mean the same for a bearing ball and a hull.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  double spread = 0.0;
  for (const Eigen::Vector3d& p : points) spread = std::max(spread, (p - centroid).norm());
  if (!(spread > 0.0)) return std::nullopt;
  const double scale = 1.0 / spread;
  std::array<double, kParameters> q = pack(similar(start, -centroid, scale));
  ceres::Problem problem;
  for (const Eigen::Vector3d& p : points) {
    auto* cost = new ceres::AutoDiffCostFunction<DistanceResidual, 1, kParameters>(
        new DistanceResidual{start.kind, (p - centroid) * scale});
    problem.AddResidualBlock(cost, nullptr, q.data());
  }
  const std::vector<int> unused = unusedParameters(start.kind);
  if (!unused.empty())
    problem.SetManifold(q.data(), new ceres::SubsetManifold(kParameters, unused));
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 100;
  options.function_tolerance = 1e-16;  // exact tessellations fit to rounding
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-14;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  const RecognisedSurface fitted =
      similar(similar(unpack(similar(start, -centroid, scale), q), Eigen::Vector3d::Zero(), spread),
              centroid, 1.0);
  const bool finite = fitted.point.allFinite() && fitted.axis.allFinite() &&
                      std::isfinite(fitted.radius + fitted.minor_radius + fitted.angle);
  if (!summary.IsSolutionUsable() || !finite || !determined(problem, start.kind))
    return std::nullopt;
  return fitted;
}

}  // namespace detail
}  // namespace vcontact::geometry
