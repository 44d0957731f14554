#pragma once
// The patches of `columns` against those of an exact method on the same pose: the same regions,
// each to the column method's own accuracy (peg_patches_test, columns_patches_test).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "volume/contact_volume.hpp"

namespace vcontact::test {

/// Tolerances of a columns patch against the exact one. V: the tolerance the refinement is
/// asked for (1e-3, ColumnOptions), or the estimate columns reports when larger (the larger of
/// its last two level-to-level changes: 2e-4 to 4e-3 on the peg, whose errors are 2e-5 to
/// 3e-4). The estimate alone is not a bound: a dumbbell cap's converges to 2.9e-5 and errs by
/// 3.5e-5. The normal comes from 64-line axis passes, whose
/// rim cells tilt it by up to a few degrees on a region a few cells wide (1.5° seen on the
/// peg's 0.3 mm crescents): 0.05 rad. Depth and area from the final grid, whose lines sample the
/// region at cell centres: 1 % (0.4 % seen). The centroid within 2e-4 of the pair's size (about
/// a cell of the finest grid).
inline void expectColumnsAgree(const volume::ContactPatches& exact,
                               const volume::ContactPatches& columns, double size) {
  ASSERT_EQ(columns.patches.size(), exact.patches.size());
  for (const volume::ContactVolume& e : exact.patches) {
    const volume::ContactVolume& c = *std::min_element(
        columns.patches.begin(), columns.patches.end(), [&e](const auto& x, const auto& y) {
          return (x.p_WC - e.p_WC).norm() < (y.p_WC - e.p_WC).norm();
        });
    EXPECT_NEAR(c.volume, e.volume, std::max(c.relative_error, 1e-3) * e.volume);
    EXPECT_LT(std::acos(std::clamp(c.n_W.dot(e.n_W), -1.0, 1.0)), 0.05);
    EXPECT_NEAR(c.depth, e.depth, 0.01 * e.depth);
    EXPECT_NEAR(c.area, e.area, 0.01 * e.area);
    EXPECT_LE((c.p_WC - e.p_WC).norm(), 2e-4 * size);
  }
}

}  // namespace vcontact::test
