#include "volume/methods.hpp"

#include <array>
#include <string>
#include <variant>

#include "geometry/error.hpp"
#include "volume/analytic/primitive_on_plane.hpp"
#include "volume/cgal/corefinement.hpp"
#include "volume/columns/columns.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume/recovered/recovered_query.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using geometry::Shape;

bool isMesh(const Shape& s) { return std::holds_alternative<geometry::Mesh>(s); }
bool isHalfspace(const Shape& s) { return std::holds_alternative<geometry::HalfSpace>(s); }

bool meshAndHalfspace(const Shape& a, const Shape& b) {
  return (isMesh(a) && isHalfspace(b)) || (isMesh(b) && isHalfspace(a));
}
bool twoMeshes(const Shape& a, const Shape& b) { return isMesh(a) && isMesh(b); }
bool meshAndMeshOrHalfspace(const Shape& a, const Shape& b) {
  return twoMeshes(a, b) || meshAndHalfspace(a, b);
}

// The backends as ComputeFn: each takes what it uses of the query.

ContactPatches analytic(const Shape& a, const Isometry3d& X_WA, const Shape& b,
                        const Isometry3d& X_WB, const QueryOptions&, DepthField*, ContactCache*) {
  return singlePatch(analyticContact(a, X_WA, b, X_WB));
}

ContactPatches halfspace(const Shape& a, const Isometry3d& X_WA, const Shape& b,
                         const Isometry3d& X_WB, const QueryOptions&, DepthField*, ContactCache*) {
  return halfspaceClipContact(a, X_WA, b, X_WB);
}

ContactPatches cgal(const Shape& a, const Isometry3d& X_WA, const Shape& b, const Isometry3d& X_WB,
                    const QueryOptions&, DepthField*, ContactCache*) {
  return cgalContact(a, X_WA, b, X_WB);
}

ContactPatches fast(const Shape& a, const Isometry3d& X_WA, const Shape& b, const Isometry3d& X_WB,
                    const QueryOptions& options, DepthField*, ContactCache* cache) {
  return fastContact(a, X_WA, b, X_WB, cache ? &cache->meshMesh() : nullptr,
                     options.depth == DepthMode::kDeepest);
}

ContactPatches columns(const Shape& a, const Isometry3d& X_WA, const Shape& b,
                       const Isometry3d& X_WB, const QueryOptions& options, DepthField* field,
                       ContactCache*) {
  const ColumnOptions grid = options.fixed_resolution > 0
                                 ? ColumnOptions::fixed(options.fixed_resolution)
                                 : ColumnOptions{};
  return columnsPatches(a, X_WA, b, X_WB, field, grid);
}

ContactPatches recovered(const Shape& a, const Isometry3d& X_WA, const Shape& b,
                         const Isometry3d& X_WB, const QueryOptions& options, DepthField*,
                         ContactCache* cache) {
  return recoveredContact(a, X_WA, b, X_WB, options, cache);
}

constexpr std::array kTable{
    MethodRow{Method::kAnalytic, "analytic", analyticSupports, analytic, false,
              "the cylinder's quadrature estimate (1e-9 or better); NaN for the sphere and box "
              "closed forms",
              "takes a sphere, cylinder or box against a half-space", true, false},
    MethodRow{Method::kHalfspace, "halfspace", meshAndHalfspace, halfspace, true,
              "NaN (exact polyhedral clip)", "clips a mesh by a half-space", true, false},
    MethodRow{Method::kCgal, "cgal", meshAndMeshOrHalfspace, cgal, true, "NaN (exact corefinement)",
              "intersects two meshes, or a mesh and a half-space", false, false},
    MethodRow{Method::kFast, "fast", twoMeshes, fast, true, "NaN (exact local surface integration)",
              "intersects two meshes (for a mesh against a half-space use halfspace)", true, false},
    MethodRow{Method::kColumns, "columns", meshAndMeshOrHalfspace, columns, false,
              "the change of V between the last two grid levels; inf on a fixed grid",
              "integrates columns through two meshes, or a mesh and a half-space", false, true},
    MethodRow{Method::kRecovered, "recovered", meshAndMeshOrHalfspace, recovered, false,
              "NaN; the bound on |V - V_true| is in the result's surface use",
              "computes a mesh on its recognised surfaces (closed forms, else the exact "
              "polyhedral method) against a half-space or another mesh",
              false, false},
};

}  // namespace

std::span<const MethodRow> methodTable() { return kTable; }

const MethodRow& methodRow(Method method) {
  for (const MethodRow& row : kTable) {
    if (row.id == method) return row;
  }
  throw std::logic_error("volume method " + std::to_string(static_cast<int>(method)) +
                         " has no row in the method table");
}

std::string methodName(Method method) { return std::string(methodRow(method).name); }

Method parseMethod(const std::string& name) {
  std::string names;
  for (const MethodRow& row : kTable) {
    if (row.name == name) return row.id;
    names += (names.empty() ? "" : ", ") + std::string(row.name);
  }
  throw InputError("volume method", "unknown method '" + name + "'; expected one of " + names);
}

}  // namespace vcontact::volume
