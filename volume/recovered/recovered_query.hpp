#pragma once
// The `recovered` row of the method table (methods.hpp): a mesh on its recognised surfaces
// (recoverSurface, made once per mesh) against a half-space or another mesh, either order.
//
//   mesh on a half-space  the closed form where the faces within reach lie on one sphere, one
//                         capped cylinder or one solid of revolution (recovered_surface.hpp);
//                         else, with QueryOptions::refine, the polyhedron refined towards its
//                         curved surfaces (refinement.hpp); else the exact clip (`halfspace`)
//   two meshes            a solid of revolution in a cylindrical bore of the other, by slices,
//                         a patch per run of the axis (bore_pair.hpp, pin_in_bore.hpp); else,
//                         with refine, both refined (refinement.hpp); else `fast`
//
// ContactPatches::surface says which was used, why a closed form did not apply, and the bound
// on |V − V_true|. Every patch and the aggregate carry Method::kRecovered.

#include <Eigen/Geometry>

#include "geometry/primitives.hpp"
#include "volume/contact.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::volume {

/// @pre handles(Method::kRecovered, a, b): a mesh and a half-space, or two meshes
/// @throws InputError when recognition refuses a mesh (not closed, not oriented)
ContactPatches recoveredContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                                const geometry::Shape& b, const Eigen::Isometry3d& X_WB,
                                const QueryOptions& options, ContactCache* cache);

}  // namespace vcontact::volume
