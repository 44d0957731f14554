// PatchTracker (dynamics/trackers/patch_tracker.hpp): the slot rules 1–4 on hand-made patches.

#include "dynamics/trackers/patch_tracker.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace vcontact::dynamics {
namespace {

const Eigen::Isometry3d kIdentity = Eigen::Isometry3d::Identity();

volume::ContactVolume patchAt(double x, double r_gyr = 2e-3,
                              const Eigen::Vector3d& n = Eigen::Vector3d::UnitZ()) {
  volume::ContactVolume cv;
  cv.volume = 1e-9;
  cv.p_WC = Eigen::Vector3d(x, 0.0, 0.0);
  cv.n_W = n;
  cv.r_gyr = r_gyr;
  return cv;
}

// A tracker whose slots hold `patches` (slots in order) after one accepted step.
PatchTracker tracking(int slots, const std::vector<volume::ContactVolume>& patches) {
  PatchTracker t(slots);
  PatchMatch m;
  t.match(patches, kIdentity, kIdentity, m);
  t.update(patches, m, kIdentity, kIdentity);
  return t;
}

TEST(PatchTracker, NewPatchesTakeTheLowestFreeSlots) {
  const PatchTracker t(3);
  PatchMatch m;
  t.match({patchAt(0.0), patchAt(0.05)}, kIdentity, kIdentity, m);
  EXPECT_EQ(m.slot, (std::vector<int>{0, 1}));
  EXPECT_EQ(m.host, m.slot);
  EXPECT_EQ(m.without_slot, 0);
}

TEST(PatchTracker, APatchThatMovedALittleKeepsItsSlot) {
  // slot 0 at x = 0, slot 1 at x = 50 mm; the patches come back in the other order, each moved
  // 1 mm (< 2 r_gyr = 4 mm)
  const PatchTracker t = tracking(2, {patchAt(0.0), patchAt(0.05)});
  PatchMatch m;
  t.match({patchAt(0.051), patchAt(0.001)}, kIdentity, kIdentity, m);
  EXPECT_EQ(m.slot, (std::vector<int>{1, 0}));
}

TEST(PatchTracker, BodyMotionWidensTheReach) {
  // The payload moved 20 mm along x since the record: a patch 20 mm on (five times 2 r_gyr)
  // is still the same one, because the relative motion at the centroid is added to the reach.
  const PatchTracker t = tracking(2, {patchAt(0.0)});
  PatchMatch m;
  t.match({patchAt(0.02)}, kIdentity, kIdentity, m);
  EXPECT_EQ(m.slot, (std::vector<int>{1})) << "without the motion it is a new patch";
  Eigen::Isometry3d X_WA = kIdentity;
  X_WA.translation().x() = 0.02;
  t.match({patchAt(0.02)}, X_WA, kIdentity, m);
  EXPECT_EQ(m.slot, (std::vector<int>{0}));
}

TEST(PatchTracker, NormalsBeyondSixtyDegreesAreDifferentPatches) {
  const PatchTracker t = tracking(2, {patchAt(0.0)});
  PatchMatch m;
  const double a59 = 59.0 * std::numbers::pi / 180.0, a61 = 61.0 * std::numbers::pi / 180.0;
  t.match({patchAt(0.0, 2e-3, {std::sin(a59), 0.0, std::cos(a59)})}, kIdentity, kIdentity, m);
  EXPECT_EQ(m.slot[0], 0);
  t.match({patchAt(0.0, 2e-3, {std::sin(a61), 0.0, std::cos(a61)})}, kIdentity, kIdentity, m);
  EXPECT_EQ(m.slot[0], 1);
}

TEST(PatchTracker, AVanishedPatchFreesItsSlotAfterTheStep) {
  PatchTracker t = tracking(2, {patchAt(0.0), patchAt(0.05)});
  PatchMatch m;
  const std::vector<volume::ContactVolume> left = {patchAt(0.05)};
  t.match(left, kIdentity, kIdentity, m);
  EXPECT_EQ(m.slot, (std::vector<int>{1}));
  EXPECT_TRUE(t.records()[0].active) << "records change after an accepted step only";
  t.update(left, m, kIdentity, kIdentity);
  EXPECT_FALSE(t.records()[0].active);
  EXPECT_TRUE(t.records()[1].active);
  // the freed slot takes the next new patch
  t.match({patchAt(0.05), patchAt(0.2)}, kIdentity, kIdentity, m);
  EXPECT_EQ(m.slot, (std::vector<int>{1, 0}));
}

TEST(PatchTracker, ASplitKeepsTheSlotWithTheNearerHalf) {
  // one patch of r_gyr 5 mm at x = 0 splits into halves at −3 mm and +4 mm
  const PatchTracker t = tracking(4, {patchAt(0.0, 5e-3)});
  PatchMatch m;
  t.match({patchAt(0.004), patchAt(-0.003)}, kIdentity, kIdentity, m);
  EXPECT_EQ(m.slot, (std::vector<int>{1, 0}));
}

TEST(PatchTracker, AMergeKeepsTheNearerSlotAndDropsTheOther) {
  PatchTracker t = tracking(4, {patchAt(-0.003), patchAt(0.004)});
  PatchMatch m;
  const std::vector<volume::ContactVolume> one = {patchAt(0.0015, 5e-3)};
  t.match(one, kIdentity, kIdentity, m);
  EXPECT_EQ(m.slot, (std::vector<int>{1}));  // 2.5 mm from slot 1, 4.5 mm from slot 0
  t.update(one, m, kIdentity, kIdentity);
  EXPECT_FALSE(t.records()[0].active);
  EXPECT_TRUE(t.records()[1].active);
}

TEST(PatchTracker, PatchesBeyondTheSlotsReadTheNearestSlot) {
  const PatchTracker t = tracking(2, {patchAt(0.0), patchAt(0.05)});
  PatchMatch m;
  t.match({patchAt(0.0), patchAt(0.05), patchAt(0.04), patchAt(-0.2)}, kIdentity, kIdentity, m);
  EXPECT_EQ(m.slot, (std::vector<int>{0, 1, -1, -1}));
  EXPECT_EQ(m.host, (std::vector<int>{0, 1, 1, 0}));
  EXPECT_EQ(m.without_slot, 2);
}

TEST(PatchTracker, EqualDistancesAreBrokenByIndexDeterministically) {
  // two patches exactly as far from the one record: the first patch gets it
  const PatchTracker t = tracking(2, {patchAt(0.0)});
  PatchMatch m;
  t.match({patchAt(0.001), patchAt(-0.001)}, kIdentity, kIdentity, m);
  EXPECT_EQ(m.slot, (std::vector<int>{0, 1}));
  t.match({patchAt(-0.001), patchAt(0.001)}, kIdentity, kIdentity, m);
  EXPECT_EQ(m.slot, (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace vcontact::dynamics
