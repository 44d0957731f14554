#pragma once
// Synthetic rig records: the motion programs of the identification procedure of MODEL.md §4,
// replayed through a known model, with seeded Gaussian noise added. They are what the tests
// and the bundled example datasets are made of; every such dataset says so in its notes.
//
// Profiles (plate: the half-space; punch: cylinder R = 10 mm, L = 20 mm, face down;
// ball: sphere R = 10 mm):
//   loading        punch pressed to 50 nm and released (kv; misalignment shows in tx, ty)
//   impacts        ball, four impacts at 0.2–0.8 mm/s, 10 µm deep (damping)
//   friction-ramp  punch at 20 nm, sliding speed v = v_max sin³(2πt/T) through zero (stick,
//                  presliding, breakaway: stribeck, bristle)
//   drive          punch at 20 nm, six constant speeds 0.5–15 mm/s both ways (coulomb, viscous)
//   dwell          punch at 20 nm, slide–stop–restart with stops of 0.1, 0.5, 1.5 s (dwell)
//   slide-spin     punch at 20 nm, sliding slows while the spin grows (spin, contensou)
//   rolling        ball at 5 µm rolling without slip, rocking (rolling_resistance)
//   indentation    ball pressed at 6.7 µm/s to 8 µm, held 1 s, released at the same rate, one
//                  force channel fz (power_law, viscoelastic, adhesion: the normal law)

#include <string>
#include <vector>

#include "dynamics/model.hpp"
#include "validation/dataset.hpp"

namespace vcontact::validation {

/// The prescribed motion of a profile as a dataset without measured wrench: samples, the
/// kinematic columns, payload, plate, outputs and the profile's default noise σ.
/// @throws InputError on an unknown profile or fewer than 3 samples
Dataset rigMotion(const std::string& profile, std::size_t samples);

/// Replays `dataset` through `truth`, adds N(0, σ²) noise with σ = dataset.noise (seeded,
/// reproducible; none for an output without σ) and stores the result as the measured wrench
/// columns of the outputs.
void synthesizeMeasurement(Dataset& dataset, const dynamics::Model& truth, unsigned seed);

}  // namespace vcontact::validation
