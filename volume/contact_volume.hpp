#pragma once
// The seam between geometry and forces (ARCHITECTURE.md): every volume backend fills this
// struct, every force model reads it. Definitions follow docs/MODEL.md §1.
//
// Frames: all quantities are in the world frame W. Body B1 ("a", the payload) and body B2
// ("b", the plate); the normal n points out of B into A.

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "geometry/moments.hpp"

namespace vcontact::volume {

/// The key of a row of the method table (volume/methods.hpp), which alone maps it to its
/// name and backend.
enum class Method { kAnalytic, kHalfspace, kCgal, kFast, kColumns, kRecovered };

/// The row's name ("analytic", "halfspace", ...).
std::string methodName(Method method);
/// Inverse of methodName.
/// @throws InputError naming the table's methods when `name` is none of them
Method parseMethod(const std::string& name);

struct ContactVolume {
  double volume = 0.0;                             ///< V, m³ (0: no contact)
  Eigen::Vector3d p_WC = Eigen::Vector3d::Zero();  ///< p_c, the centroid C in W, m
  Eigen::Vector3d n_W = Eigen::Vector3d::UnitZ();  ///< n, unit, out of B into A
  Eigen::Matrix3d J_v = Eigen::Matrix3d::Zero();   ///< ∫((ρ·ρ)I − ρρᵀ)dV about p_c, m⁵
  Eigen::Matrix3d J_s = Eigen::Matrix3d::Zero();   ///< surface inertia tensor, m⁵
  double area = 0.0;                               ///< contact area A, m²
  double r_gyr = 0.0;                              ///< radius of gyration about n, m
  double depth = 0.0;                              ///< deepest penetration along n, m
  Method method = Method::kAnalytic;
  /// Estimated relative error of V from the method itself (quadrature, grid); NaN where the
  /// method is exact for the shapes it was given (closed forms, polyhedral clips).
  double relative_error = std::numeric_limits<double>::quiet_NaN();

  bool inContact() const { return volume > 0.0; }
};

/// The interference of a pair split into its contact regions: the volumetric model is defined
/// per connected region of A ∩ B, each with its own V, p_c, n, J_s and friction state
/// (MODEL.md §1). The pair's total V is the sum of the patches' V.
/// What a contact was computed on. Every method but `recovered` computes on the shapes as they
/// are (kShape); `recovered` on a mesh's recognised surfaces where a closed form applies, and
/// otherwise on a refinement of the polyhedron towards them, or on the polyhedron itself, its
/// fallback (docs/SURFACES.md).
enum class Representation {
  kShape,             ///< the shapes as given: the polyhedron of a mesh (its name: "mesh")
  kSphere,            ///< a recognised sphere on a half-space, closed form
  kCylinder,          ///< a cylinder closed by flat ends on a half-space, closed form
  kRevolution,        ///< a solid of revolution on a half-space, by closed-form slices
  kRevolutionInBore,  ///< a solid of revolution in a cylindrical bore of the other mesh, by slices
  kRefined,           ///< the polyhedron refined towards its surfaces until V converged
};

/// "mesh", "sphere", "cylinder", "revolution", "revolution_in_bore", "refined".
const char* representationName(Representation representation);

/// One part of the faces that can reach the partner, of a refined contact: which body ("A" or
/// "B"), the surface ("cone", "concave cylinder", "plane", "free-form"), how many faces, and
/// what represents them: "refined" (split and projected onto the recognised surface), "exact"
/// (planes: the faces are the surface) or "polyhedral" (free-form faces, kept as they are).
struct PatchPart {
  std::string body;
  std::string surface;
  int faces = 0;
  std::string representation;
};

/// How a `recovered` query went (ContactPatches::surface); the other methods leave it as is.
struct SurfaceUse {
  Representation representation = Representation::kShape;
  /// Why no closed form applied (a refined or polyhedral result); empty otherwise.
  std::string reason;
  /// A bound on |V − V_true|, m³ (docs/SURFACES.md): for a closed form the contact area times
  /// the surfaces' fit residual plus the closed form's own error; refined, the Richardson
  /// estimate plus the same residual term; for the polyhedron, the area times the largest chord
  /// gap of the faces that can reach the partner (NaN where free-form faces reach it, or where
  /// no query on recovered surfaces was made).
  double volume_error_bound = std::numeric_limits<double>::quiet_NaN();
  /// kRefined: what the faces within reach were computed on, per body and surface; the
  /// refinement level k of the finest evaluation, and whether its error estimate met the
  /// tolerance (false: the level cap came first).
  std::vector<PatchPart> parts;
  int level = 0;
  bool converged = true;
};

struct ContactPatches {
  /// The connected components of A ∩ B, each a full ContactVolume of its own region, ordered
  /// by sortPatches.
  std::vector<ContactVolume> patches;
  /// The whole A ∩ B as one region (one centroid, one normal): the single-region figures.
  ContactVolume aggregate;
  /// `recovered` queries: the surfaces it was computed on, and why where it fell back.
  SurfaceUse surface;

  bool inContact() const { return !patches.empty(); }
};

/// The deterministic order of patches: decreasing V, ties by the lexicographic order of the
/// centroid's (x, y, z) in W. The order depends on no face index, so every method lists the
/// patches of one pose alike up to its own accuracy.
void sortPatches(std::vector<ContactVolume>& patches);

/// A pair whose interference is one region: that region is the aggregate and the only patch
/// (none when `cv` is not in contact).
ContactPatches singlePatch(const ContactVolume& cv);

/// The penetration depth δ(s) sampled on the contact plate S (MODEL.md §1, V = ∫_S δ dS),
/// for a force law integrated pointwise over the plate; filled by the methods that sample it
/// (methods.hpp, fills_depth_field).
struct DepthField {
  std::vector<Eigen::Vector3d> points_W;  ///< where each sample's column meets the plate S, m
  std::vector<double> depth;              ///< δ along n, m (> 0)
  double cell_area = 0.0;                 ///< dS of every sample's cell on the plate, m²
};

/// Fills a ContactVolume from the region's central moments, all in W.
///   J_v = tr(Σ) I − Σ,  Σ = ∫ρρᵀ dV about p_c;
///   J_s = tr(Σ_s) I − Σ_s,  Σ_s = P Σ P,  P = I − n nᵀ
/// (the Winkler columns run along n, so ∫_S f(s) δ(s) dS = ∫_V f(P p) dV, MODEL.md §1);
///   r_gyr² = nᵀ J_s n / V.
/// @pre V > 0, n unit.
ContactVolume assembleContactVolume(double V, const Eigen::Vector3d& p_c,
                                    const Eigen::Matrix3d& Sigma, const Eigen::Vector3d& n,
                                    double area, double depth, Method method);

/// The contact of a region from its raw moments M about a point o (MODEL.md §1):
///   p_c = o + c,  c = m1 / m0;   Σ = m2 − m0 c cᵀ (the central second moment);
/// then assembleContactVolume(m0, p_c, Σ, n, ...).
/// @param M    moments about o, W axes
/// @param p_Wo o in W
/// @pre M.m0 > 0, n unit
ContactVolume contactFromMoments(const geometry::Moments& M, const Eigen::Vector3d& p_Wo,
                                 const Eigen::Vector3d& n, double area, double depth,
                                 Method method);

/// The same for moments taken in the axes of a frame F: p_c = X_WF o_F + R_WF c,
/// Σ_W = R_WF Σ_F R_WFᵀ (o and c are mapped separately, so that c keeps its digits when o is
/// far from the region).
/// @param M    moments about o, F axes
/// @param p_Fo o in F
/// @param X_WF pose of F in W
/// @pre M.m0 > 0, n unit
ContactVolume contactFromMoments(const geometry::Moments& M, const Eigen::Vector3d& p_Fo,
                                 const Eigen::Isometry3d& X_WF, const Eigen::Vector3d& n,
                                 double area, double depth, Method method);

/// The same contact seen with the bodies swapped: the normal flips, nothing else changes.
ContactVolume swapped(ContactVolume cv);
/// The same for every patch and the aggregate.
ContactPatches swapped(ContactPatches contact);

}  // namespace vcontact::volume
