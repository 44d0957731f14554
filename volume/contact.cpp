#include "volume/contact.hpp"

#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume/kernels/mesh_convexity.hpp"
#include "volume/methods.hpp"
#include "volume/speck_floor.hpp"

namespace vcontact::volume {
namespace {

[[noreturn]] void unsupported(const MethodRow& row, const geometry::Shape& a,
                              const geometry::Shape& b) {
  throw InputError("volume method " + std::string(row.name),
                   "cannot compute " + geometry::describe(a) + " against " + geometry::describe(b) +
                       " with this method; it " + std::string(row.scope));
}

/// The first row that takes the pair among those `eligible` accepts.
template <class Eligible>
Method firstHandling(const geometry::Shape& a, const geometry::Shape& b, Eligible eligible,
                     const char* what) {
  for (const MethodRow& row : methodTable()) {
    if (eligible(row) && row.handles(a, b)) return row.id;
  }
  throw InputError("", std::string("no ") + what + " in this build handles " +
                           geometry::describe(a) + " against " + geometry::describe(b));
}

}  // namespace

void dropSpecks(std::vector<ContactVolume>& patches) {
  double total = 0.0;
  for (const ContactVolume& p : patches) total += p.volume;
  const double floor = kPatchVolumeFloor * total;
  while (!patches.empty() && patches.back().volume < floor) patches.pop_back();
}

Method defaultMethod(const geometry::Shape& a, const geometry::Shape& b) {
  return firstHandling(
      a, b, [](const MethodRow& row) { return row.is_default; }, "volume method");
}

Method defaultDepthFieldMethod(const geometry::Shape& a, const geometry::Shape& b) {
  return firstHandling(
      a, b, [](const MethodRow& row) { return row.fills_depth_field; },
      "volume method that fills a depth field");
}

bool handles(Method method, const geometry::Shape& a, const geometry::Shape& b) {
  return methodRow(method).handles(a, b);
}

void requireHandles(Method method, const geometry::Shape& a, const geometry::Shape& b) {
  const MethodRow& row = methodRow(method);
  if (!row.handles(a, b)) unsupported(row, a, b);
}

bool fillsDepthField(Method method) { return methodRow(method).fills_depth_field; }

std::vector<MethodDescription> describeMethods() {
  std::vector<MethodDescription> out;
  for (const MethodRow& row : methodTable()) {
    out.push_back({row.id, row.name, row.exact, row.error_estimate, row.scope, row.is_default,
                   row.fills_depth_field});
  }
  return out;
}

ContactCache::ContactCache() : mesh_mesh_(std::make_unique<MeshMeshCache>()) {}
ContactCache::~ContactCache() = default;
ContactCache::ContactCache(ContactCache&&) noexcept = default;
ContactCache& ContactCache::operator=(ContactCache&&) noexcept = default;

bool convexSolid(const geometry::Shape& shape) {
  const auto* mesh = std::get_if<geometry::Mesh>(&shape);
  return mesh == nullptr || isConvex(mesh->mesh);
}

ContactPatches computeContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                              const geometry::Shape& b, const Eigen::Isometry3d& X_WB,
                              const QueryOptions& options, DepthField* field, ContactCache* cache) {
  // value_or would evaluate the default eagerly
  const Method method = options.method ? *options.method
                        : field        ? defaultDepthFieldMethod(a, b)
                                       : defaultMethod(a, b);
  const MethodRow& row = methodRow(method);
  if (!row.handles(a, b)) unsupported(row, a, b);
  if (field && !row.fills_depth_field) {
    throw InputError("volume method " + std::string(row.name),
                     "it does not sample the depth field asked for");
  }
  ContactPatches out = row.compute(a, X_WA, b, X_WB, options, field, cache);
  dropSpecks(out.patches);
  return out;
}

}  // namespace vcontact::volume
