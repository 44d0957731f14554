#pragma once
// Two meshes on their recovered surfaces, a pin in a bore, by slices (docs/SURFACES.md, "Two
// meshes: a pin in a bore"): when one body is one solid of revolution (RecoveredBody::
// revolution) and the faces of the other within its reach lie on one concave cylinder (the
// bore) and on planes across the bore's axis (the faces the bore opens onto), the
// interference is computed slice by slice across the pin's axis (volume/recovered/pin_in_bore.hpp):
// in closed form when the axes are parallel, in the polar angle when the pin is tilted; no
// refinement.

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "volume/recovered/recovered_surface.hpp"

namespace vcontact::volume {

/// The contact of `pin` (pose X_WP) in the bore of `block` (pose X_WB) by slices,
/// representation kRevolutionInBore, n out of the block into the pin; nothing when the
/// slices do not apply, with `reason` saying why: the pin is not one solid of revolution;
/// the block's faces within reach of the pin's bounding cylinder are free-form, on another
/// curved surface than one concave cylinder, on a plane that is not across the bore's axis
/// (the pin near a side face), or on two planes on one side (a step or a counterbore); the
/// pin reaches beyond the bore where no plane closes the block. A bore parallel to the pin
/// (|cos| of the axes' angle within 1e-9 of 1) is sliced in closed form (revolutionInBore),
/// a tilted one in the polar angle (revolutionInTiltedBore).
///
/// volume_error_bound: the contact area times the largest fit residual of the surfaces used
/// and the quadrature's estimate times V; parallel, plus what taking the axes and planes as
/// parallel costs: the bore's section is an ellipse whose semi-axes are R and R/cos β (area
/// times R(1/cos β − 1)), and a plane tilted by γ from across the axis moves across the pin's
/// disc by r·tan γ (the planes' crescents times r·tan γ).
std::optional<RecoveredContact> boreContact(const RecoveredBody& pin, const Eigen::Isometry3d& X_WP,
                                            const RecoveredBody& block,
                                            const Eigen::Isometry3d& X_WB, std::string& reason);

}  // namespace vcontact::volume
