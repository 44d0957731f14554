#pragma once
// One entry point over every backend: the interference of two placed shapes by a chosen
// method, or by the best method the pair allows. Which methods exist, which shapes each takes
// and which backend computes it is the method table (volume/methods.hpp); everything here
// reads it.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/primitives.hpp"
#include "geometry/surface_recognition.hpp"
#include "geometry/triangle_mesh.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::volume {

struct MeshMeshCache;     // fast/surface_integration.hpp
struct RecoveredSurface;  // recovered/recovered_surface.hpp: opaque above volume/

/// Whether a query computes ContactVolume::depth, the deepest column d = max over the plate of
/// δ(s) (MODEL.md §1), for the one method whose depth is a pass of its own (QueryOptions::depth).
/// By default it does not: `fast`'s exact depth pass (depth/deepest_column.hpp) makes a query on
/// two curved meshes 3–4× as long (benchmarks/README.md, "Depth on demand"), and neither the force
/// model nor any other field needs it. Ask for kDeepest where d is shown or used.
enum class DepthMode {
  kDeepest,  ///< every method fills depth: `fast` runs its exact depth pass
  kSkip,     ///< the default: `fast` leaves depth NaN; every other method fills it all the
             ///< same (analytic, halfspace, columns: a by-product; cgal: its corefinement
             ///< dwarfs the pass), and every other field is the same to the bit either way
};

/// How a query is computed.
struct QueryOptions {
  /// The method (default: defaultMethod, or defaultDepthFieldMethod when a depth field is
  /// asked for).
  std::optional<Method> method;
  /// > 0: sample a method's grid at this many lines per side, never refined, so that every
  /// query costs the same (a simulation's right-hand side) and gives no error estimate;
  /// 0: the method's own refinement. Methods without a grid ignore it.
  int fixed_resolution = 0;
  /// kSkip (the default) spares `fast` its exact depth pass, so that ContactVolume::depth of
  /// a `fast` query is NaN unless kDeepest is asked for. Callers that show or use depth ask:
  /// `vcontact volume` (table and --json), Python's contact(depth=True), the validation
  /// replay (its regimes fit V against d), a simulation's output samples (Simulator).
  DepthMode depth = DepthMode::kSkip;
  /// `recovered` only: where no closed form applies and curved recognised faces reach the
  /// partner, refine the polyhedron towards them until V converges (recovered/refinement.hpp;
  /// a query of seconds) instead of falling back to the exact polyhedral method. Off by default
  /// (simulations, replays); `vcontact volume --surface recovered` turns it on.
  bool refine = false;
};

/// The method used when none is asked for: the first default row of the table that takes
/// the pair (analytic for a primitive against a half-space, the exact half-space clip for a
/// mesh against a half-space, the exact local surface integration (fast,
/// fast/surface_integration.hpp) for two meshes).
/// @throws InputError when no default method handles the pair
Method defaultMethod(const geometry::Shape& a, const geometry::Shape& b);

/// The first method of the table that fills a depth field and takes the pair (columns).
/// @throws InputError when no such method handles the pair
Method defaultDepthFieldMethod(const geometry::Shape& a, const geometry::Shape& b);

/// Does `method` compute the contact of these shapes (whatever their poses)? The row's
/// predicate (methods.hpp): analytic: a sphere, cylinder or box against a half-space;
/// halfspace: a mesh against a half-space; cgal: two meshes, or a mesh and a half-space; fast:
/// two meshes; columns: two meshes, or a mesh and a half-space. Either order.
bool handles(Method method, const geometry::Shape& a, const geometry::Shape& b);
/// Throws the InputError a query by `method` would throw for these shapes (naming both and
/// what the method computes) unless it handles them: for readers that check before a run.
void requireHandles(Method method, const geometry::Shape& a, const geometry::Shape& b);

/// Can `method` fill a DepthField (its row's fills_depth_field)?
bool fillsDepthField(Method method);

/// What the method table (methods.hpp) says of one method, for help texts and readers that
/// describe the methods without dispatching on them.
struct MethodDescription {
  Method id;
  std::string_view name;            ///< as in files and on the command line
  bool exact;                       ///< exact for every pair it takes (up to rounding)
  std::string_view error_estimate;  ///< what ContactVolume::relative_error holds
  std::string_view scope;           ///< what it computes ("clips a mesh by ...")
  bool is_default;                  ///< a default for the pairs it takes (defaultMethod)
  bool fills_depth_field;           ///< can fill a DepthField
};

/// Every method of the table, in its order (the order defaultMethod tries the default ones).
std::vector<MethodDescription> describeMethods();

/// Does this shape bound a convex solid? Primitives and half-spaces do; a mesh does when it is
/// closed and convex (kernels/mesh_convexity.hpp, cached per mesh). Two convex solids meet in one
/// convex region, so a pair of them has one contact patch whatever the poses.
bool convexSolid(const geometry::Shape& shape);

/// What a pair of shapes keeps between queries at nearby poses (one per pair and thread;
/// used by the methods that gain from it: `fast`, MeshMeshCache). Opaque above volume/: made
/// once per pair, then handed to every query of that pair.
class ContactCache {
 public:
  ContactCache();
  ~ContactCache();
  ContactCache(ContactCache&&) noexcept;
  ContactCache& operator=(ContactCache&&) noexcept;

  MeshMeshCache& meshMesh() { return *mesh_mesh_; }  ///< `fast`'s recorded leaf pairs

 private:
  std::unique_ptr<MeshMeshCache> mesh_mesh_;
};

/// The contact patches of A (the payload) and B (the plate or other body) and their aggregate
/// (ContactPatches) by options.method, specks left out (speck_floor.hpp). `fast` takes two meshes
/// only: a mesh against a half-space is refused (the halfspace clip is the exact method for it).
/// Every field of every patch is filled, except `depth` of a `fast` query (the default method
/// for two meshes), which is NaN unless options.depth is DepthMode::kDeepest.
/// @param field  if not null, filled with the δ samples of the contact (left as it was when
///               the bodies are apart); the method must fill depth fields (fillsDepthField)
/// @param cache  if not null, the pair's memory between queries (ContactCache)
/// @throws InputError when the method does not handle the pair, naming both shapes, or
///         cannot fill the depth field asked for
ContactPatches computeContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                              const geometry::Shape& b, const Eigen::Isometry3d& X_WB,
                              const QueryOptions& options = {}, DepthField* field = nullptr,
                              ContactCache* cache = nullptr);

/// The recovered surface of `mesh` (what `recovered` queries compute on): its surfaces
/// recognised on the first call for this mesh (geometry/surface_recognition.hpp), the same
/// object afterwards while the mesh lives; thread-safe. The scenario and dataset readers make
/// it at load for "surface": "recovered", so that a bad mesh is refused before a run and the
/// recognition's time is reported once.
/// @throws InputError when recognition refuses the mesh (not closed, not oriented)
std::shared_ptr<const RecoveredSurface> recoverSurface(
    const std::shared_ptr<const geometry::TriangleMesh>& mesh);
/// What recognition found on the mesh of `surface`.
const geometry::SurfaceRecognition& recognition(const RecoveredSurface& surface);
/// The wall time of that recognition, s.
double recognitionSeconds(const RecoveredSurface& surface);
/// "1 sphere", "1 cylinder, 2 planes", "6 planes, 12 free-form faces": the kinds recognised,
/// with counts, for summaries.
std::string recognisedKinds(const geometry::SurfaceRecognition& recognition);

}  // namespace vcontact::volume
