#pragma once
// The pairs of a scenario whose contact is computed on a body's recovered surface
// ("surface": "recovered", docs/SCENARIO.md "Recovered surfaces"), and what each used.
//
// A mesh body with a recovered surface against a half-space (either order) is queried with
// volume::RecoveredBody: where the part of the body that can reach the plane lies on one
// sphere or one capped cylinder, the contact is that closed form, one patch; elsewhere it is
// the pair's polyhedral query, with its patches. Any other pair with such a body (against a
// mesh or a primitive, with distributed friction, or with a method other than the half-space
// clip) uses the polyhedra throughout, and the summary says which and why, once.

#include <Eigen/Geometry>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "volume/contact_volume.hpp"

namespace vcontact::volume {
struct RecoveredSurface;  // volume/recovered/recovered_surface.hpp
}

namespace vcontact::dynamics {

struct Scenario;

/// A body with a recovered surface: what its recognition found (summary.json "surfaces").
struct SurfaceBodyUse {
  std::string body;
  double recognition_seconds = 0.0;  ///< s, once at load
  std::map<std::string, int> kinds;  ///< "sphere": 1, "plane": 2, "concave cylinder": 1, ...
  int free_form_faces = 0;
  double max_residual = 0.0;  ///< m, the largest vertex distance to its surface
  std::string description;    ///< volume::recognisedKinds
};

/// A pair with a body that has a recovered surface: the representation its queries used.
struct SurfacePairUse {
  std::string pair;
  /// Empty when the pair is queried on the recovered surface; otherwise why the polyhedra are
  /// used for every query.
  std::string polyhedral_reason;
  /// Queries per representation: "sphere", "cylinder" (closed forms) and "mesh".
  std::map<std::string, long> evaluations;
  /// Why queries of a recovered pair fell back to the polyhedron (each reason once).
  std::set<std::string> mesh_reasons;
};

class RecoveredPairs {
 public:
  /// Decides, per pair, whether its queries use a recovered surface.
  explicit RecoveredPairs(const Scenario& scenario);

  /// Pair k's contact at these poses (body A's pose as the model adjusted it): on the
  /// recovered surface where the pair allows it and a closed form applies, otherwise
  /// `polyhedral()` (the pair's own query); counted per representation.
  volume::ContactPatches contact(std::size_t k, const Eigen::Isometry3d& X_WA,
                                 const Eigen::Isometry3d& X_WB,
                                 const std::function<volume::ContactPatches()>& polyhedral);

  /// Starts the evaluation counts again (a new run).
  void resetCounts();

  const std::vector<SurfaceBodyUse>& bodies() const { return bodies_; }
  const std::vector<SurfacePairUse>& pairs() const { return uses_; }

 private:
  struct PairPlan {
    int use = -1;  ///< index into uses_, −1 when no body of the pair is recovered
    bool on_surface = false;
    bool swapped = false;  ///< the recovered mesh is body B, the half-space body A
    std::shared_ptr<const volume::RecoveredSurface> surface;  ///< on_surface only
  };
  std::vector<PairPlan> plans_;
  std::vector<SurfaceBodyUse> bodies_;
  std::vector<SurfacePairUse> uses_;
};

}  // namespace vcontact::dynamics
