#include "geometry/mesh_check.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "geometry/error.hpp"
#include "geometry/mass_properties.hpp"
#include "geometry/mesh_repair.hpp"

namespace vcontact::geometry {
namespace {

// A face whose area is below (kDegenerateAreaRatio · bounding-box diagonal)² carries no
// direction: its normal is rounding noise. 1e-14 leaves faces 1e-7 of the part size across
// (a 1 µm facet on a 10 m part) valid.
constexpr double kDegenerateAreaRatio = 1e-14;

std::string at(const Eigen::Vector3d& p) {
  std::ostringstream os;
  os.precision(9);
  os << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return os.str();
}

// What a repair (mesh_repair.hpp) would do about each defect, said in the rejection.
std::string weldHint() {
  std::ostringstream os;
  os << "; repairing the mesh welds vertices closer than " << kDefaultWeldTolerance
     << " of its size and, when asked, fills small holes";
  return os.str();
}
const char* const kDropZeroAreaHint = "; repairing the mesh drops zero-area faces";
const char* const kDropDuplicateHint = "; repairing the mesh drops duplicate faces";
const char* const kOrientHint = "; repairing the mesh orients its faces consistently";

[[noreturn]] void reject(std::size_t count, const std::string& what, const std::string& where,
                         const std::string& hint = "") {
  std::ostringstream os;
  os << count << " " << what << "; first " << where << hint;
  throw InputError("", os.str());
}

}  // namespace

void checkFinite(const TriangleMesh& mesh) {
  std::size_t bad = 0;
  Eigen::Index first = -1;
  for (Eigen::Index i = 0; i < mesh.vertexCount(); ++i) {
    if (!mesh.vertices.row(i).allFinite()) {
      if (bad++ == 0) first = i;
    }
  }
  if (bad > 0) {
    reject(bad,
           bad == 1 ? "vertex with a NaN or infinite coordinate"
                    : "vertices with a NaN or infinite coordinate",
           "is vertex " + std::to_string(first));
  }
}

namespace {

void checkIndices(const TriangleMesh& mesh) {
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles(f, k);
      if (v < 0 || v >= mesh.vertexCount()) {
        throw InputError("", "face " + std::to_string(f) + " refers to vertex " +
                                 std::to_string(v) + ", but the mesh has " +
                                 std::to_string(mesh.vertexCount()) + " vertices");
      }
    }
  }
}

void checkDegenerate(const TriangleMesh& mesh) {
  const double diag = bounds(mesh).size().norm();
  const double minArea2 = std::pow(kDegenerateAreaRatio * diag * diag, 2);
  std::size_t bad = 0;
  Eigen::Index first = -1;
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    const auto t = mesh.triangles.row(f);
    const bool repeated = t(0) == t(1) || t(1) == t(2) || t(0) == t(2);
    const Eigen::Vector3d a = mesh.corner(f, 0), b = mesh.corner(f, 1), c = mesh.corner(f, 2);
    const double area2 = 0.25 * (b - a).cross(c - a).squaredNorm();
    if (repeated || area2 <= minArea2) {
      if (bad++ == 0) first = f;
    }
  }
  if (bad > 0) {
    reject(bad, bad == 1 ? "degenerate face (zero area)" : "degenerate faces (zero area)",
           "is face " + std::to_string(first) + " at vertex " + at(mesh.corner(first, 0)),
           kDropZeroAreaHint);
  }
}

std::uint64_t edgeKey(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

void checkClosedAndOriented(const TriangleMesh& mesh) {
  // Count each directed edge; a closed, consistently oriented 2-manifold has every directed
  // edge exactly once and its reverse exactly once.
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(static_cast<std::size_t>(mesh.triangleCount()) * 3);
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    for (int k = 0; k < 3; ++k) {
      ++directed[edgeKey(mesh.triangles(f, k), mesh.triangles(f, (k + 1) % 3))];
    }
  }
  std::size_t boundary = 0, nonManifold = 0, misoriented = 0;
  int firstBoundary = -1, firstNonManifold = -1, firstMisoriented = -1;
  for (const auto& [key, count] : directed) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    const auto reverse = directed.find(edgeKey(b, a));
    const int rcount = reverse == directed.end() ? 0 : reverse->second;
    if (a > b && rcount > 0) continue;  // the pair is counted once, from its smaller end
    const int uses = count + rcount;
    if (uses == 1) {
      if (boundary++ == 0) firstBoundary = a;
    } else if (uses > 2) {
      if (nonManifold++ == 0) firstNonManifold = a;
    } else if (count == 2 || rcount == 2) {
      if (misoriented++ == 0) firstMisoriented = a;
    }
  }
  if (boundary > 0) {
    reject(boundary,
           std::string(boundary == 1 ? "boundary edge" : "boundary edges") + ", mesh is not closed",
           "at vertex " + at(mesh.vertex(firstBoundary)), weldHint());
  }
  if (nonManifold > 0) {
    reject(nonManifold,
           std::string(nonManifold == 1 ? "edge" : "edges") +
               " shared by more than two faces, mesh is not a manifold",
           "at vertex " + at(mesh.vertex(firstNonManifold)), kDropDuplicateHint);
  }
  if (misoriented > 0) {
    reject(misoriented,
           std::string(misoriented == 1 ? "edge" : "edges") +
               " listed in the same direction by both faces, orientation is inconsistent",
           "at vertex " + at(mesh.vertex(firstMisoriented)), kOrientHint);
  }
}

// Below this fraction of the part's own scale (its diagonal for the centroid, the trace of Σ for
// its eigenvalues) a violation is the rounding of the divergence-theorem sums, not a defect:
// 1e-9 is a million times their relative rounding on a 10^6-face part.
constexpr double kMassPropertySlack = 1e-9;

}  // namespace

// What no solid has, refused wherever a mesh's mass properties come from its faces: a centroid
// outside the bounding box, a negative principal moment of inertia, principal moments that
// break the triangle inequality (I1 + I2 >= I3). With the central second moment Σ (unit
// density), the principal moments are I_i = tr(Σ) - σ_i for Σ's eigenvalues σ_i, so the last
// two both come to an eigenvalue σ_i < 0 (I_j + I_k - I_i = 2 σ_i). A surface that passes through
// itself or holds a shell turned inside out gives them (issue 36: a centroid outside the part,
// an inertia diagonal of -204 kg m^2).
void checkMassProperties(const TriangleMesh& mesh) {
  const Moments M = meshMoments(mesh);
  const Aabb box = bounds(mesh);
  const Eigen::Vector3d c = M.centroid();
  const double reach = kMassPropertySlack * box.size().norm();
  const char* const why =
      "; no solid has that: the surface most likely passes through itself or holds a shell "
      "turned inside out";
  if ((c.array() < box.min.array() - reach).any() || (c.array() > box.max.array() + reach).any()) {
    throw InputError("", "impossible mass properties: the centroid " + at(c) +
                             " lies outside the mesh's bounds " + at(box.min) + " to " +
                             at(box.max) + why);
  }
  const Eigen::Matrix3d sigma = M.centralSecondMoment();
  const Eigen::Vector3d s = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(sigma).eigenvalues();
  if (s.minCoeff() >= -kMassPropertySlack * std::abs(sigma.trace())) return;
  const Eigen::Vector3d I = Eigen::Vector3d::Constant(sigma.trace()) - s;  // unit density
  std::ostringstream os;
  os.precision(6);
  os << "impossible mass properties: the principal moments of inertia at unit density, " << I.x()
     << ", " << I.y() << ", " << I.z() << " m^5, "
     << (I.minCoeff() < 0.0 ? "include a negative one"
                            : "break the triangle inequality (the two "
                              "smaller must add up to the largest)")
     << why;
  throw InputError("", os.str());
}

MeshCheckResult checkAndRepair(TriangleMesh& mesh) {
  if (mesh.triangleCount() == 0) throw InputError("", "mesh has no faces");
  checkFinite(mesh);
  checkIndices(mesh);
  checkDegenerate(mesh);
  checkClosedAndOriented(mesh);

  MeshCheckResult result;
  const double volume = meshMoments(mesh).m0;
  const double scale = std::pow(bounds(mesh).size().norm(), 3);
  // Below 1e-12 of the bounding cube the enclosed volume is rounding noise of the
  // divergence-theorem sum: the "solid" is flat.
  if (!(std::abs(volume) > 1e-12 * scale)) {
    throw InputError("", "mesh encloses no volume (flat or self-cancelling surface)");
  }
  if (volume < 0.0) {
    mesh.triangles.col(1).swap(mesh.triangles.col(2));
    result.flipped = true;
    result.warnings.push_back("faces were oriented inward (negative volume); flipped all " +
                              std::to_string(mesh.triangleCount()) + " faces");
  }
  result.shells = checkShells(mesh);
  checkMassProperties(mesh);
  return result;
}

}  // namespace vcontact::geometry
