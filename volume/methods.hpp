#pragma once
// The volume methods as one table (MuJoCo's collision table, Jolt's CollisionDispatch): one
// row per method, in methods.cpp. A new method is its backend file plus one row (and its CMake
// source line and its test); the dispatcher (contact.hpp), the CLI and the readers read the
// rows and know no method by name.

#include <Eigen/Geometry>
#include <span>
#include <string_view>

#include "geometry/primitives.hpp"
#include "volume/contact.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::volume {

/// Does a method take shape a (body A) against shape b (body B)? Either order is the method's
/// concern.
using HandlesFn = bool (*)(const geometry::Shape& a, const geometry::Shape& b);

/// The backend of a method, for a pair its HandlesFn accepts (@pre handles(a, b)): the
/// patches of the pair and their aggregate (ContactPatches).
/// @param field  if not null (only for a row that fills depth fields), the δ samples
/// @param cache  if not null, the pair's memory between queries
using ComputeFn = ContactPatches (*)(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                                     const geometry::Shape& b, const Eigen::Isometry3d& X_WB,
                                     const QueryOptions& options, DepthField* field,
                                     ContactCache* cache);

struct MethodRow {
  Method id;                        ///< the key ContactVolume::method carries
  std::string_view name;            ///< as in files and on the command line
  HandlesFn handles;                ///< which shape pairs it takes
  ComputeFn compute;                ///< its backend
  bool exact;                       ///< exact for every pair it takes (up to rounding)
  std::string_view error_estimate;  ///< what ContactVolume::relative_error holds
  std::string_view scope;           ///< what it computes ("clips a mesh by ..."), for refusals
  bool is_default;                  ///< a default for the pairs it takes (defaultMethod)
  bool fills_depth_field;           ///< can fill a DepthField
};

/// Every method, in the order defaultMethod tries the default ones.
std::span<const MethodRow> methodTable();

/// The row of `method`.
const MethodRow& methodRow(Method method);

}  // namespace vcontact::volume
