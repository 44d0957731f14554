#pragma once
// The floor below which computeContact (contact.hpp) leaves a patch out of the list of a
// pair's patches: specks of the facets that only the exact methods see.

#include <vector>

#include "volume/contact_volume.hpp"

namespace vcontact::volume {

/// The share of the pair's volume below which a patch is left out of ContactPatches::patches
/// (its volume stays in the aggregate). Such specks are real for the polyhedra: a 64-gon
/// peg's corner pokes 0.03–0.7 µm through a facet of its 64-gon hole, within the facets' 6 µm
/// sagitta, and cgal finds the same volume as fast. But the force model is linear in V, so a
/// speck carries less than 1e-4 of the pair's normal force, ten times below what `columns`
/// resolves (its default tolerance on V is 1e-3), and the methods could not agree on whether
/// it is there. A patch that grows past the share joins the list as a new patch from rest.
constexpr double kPatchVolumeFloor = 1e-4;

/// Removes the patches whose V is below kPatchVolumeFloor × the sum of all the patches' V.
/// @pre patches in sortPatches order (decreasing V)
void dropSpecks(std::vector<ContactVolume>& patches);

}  // namespace vcontact::volume
