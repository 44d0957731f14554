#pragma once
// The pairs of a scenario whose contact is computed on a body's recovered surface
// ("surface": "recovered", docs/SCENARIO.md "Recovered surfaces"), and what each used.
//
// A pair with a recovered mesh body against a half-space or another mesh is queried by the
// method table's `recovered` row (volume/contact.hpp): the closed form where the faces within
// reach lie on one sphere, capped cylinder or solid of revolution, or a solid of revolution in
// a cylindrical bore (a patch per run of its axis); elsewhere the exact polyhedral method, with
// its patches. Any other pair with such a body (against a primitive, with distributed friction,
// or with a method of its own) uses the polyhedra throughout, and the summary says which and
// why, once.

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "volume/contact_volume.hpp"

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
  /// Queries per representation (volume::representationName): "sphere", "cylinder",
  /// "revolution", "revolution_in_bore" (closed forms) and "mesh" (the polyhedra).
  std::map<std::string, long> evaluations;
  /// Why queries of a recovered pair fell back to the polyhedron (each reason once).
  std::set<std::string> mesh_reasons;
};

class RecoveredPairs {
 public:
  /// Decides, per pair, whether its queries use a recovered surface.
  explicit RecoveredPairs(const Scenario& scenario);

  /// The method pair k is queried with: `recovered` where the pair is on a recovered surface,
  /// else the pair's own (`asked`, empty for the default).
  std::optional<volume::Method> method(std::size_t k, std::optional<volume::Method> asked) const {
    return plans_[k].on_surface ? std::optional(volume::Method::kRecovered) : asked;
  }

  /// Counts a query of pair k by what it was computed on (ContactPatches::surface), and the
  /// reason of a fallback to the polyhedra. @pre not called for one pair from two threads
  void count(std::size_t k, const volume::ContactPatches& contact);

  /// Starts the evaluation counts again (a new run).
  void resetCounts();

  const std::vector<SurfaceBodyUse>& bodies() const { return bodies_; }
  const std::vector<SurfacePairUse>& pairs() const { return uses_; }

 private:
  struct PairPlan {
    int use = -1;  ///< index into uses_, −1 when no body of the pair is recovered
    bool on_surface = false;
  };
  std::vector<PairPlan> plans_;
  std::vector<SurfaceBodyUse> bodies_;
  std::vector<SurfacePairUse> uses_;
};

}  // namespace vcontact::dynamics
