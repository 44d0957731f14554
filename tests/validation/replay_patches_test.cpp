// Replay of a payload that touches the plate in several regions: one force model and one set
// of friction states per contact patch (MODEL.md §1), summed about the payload origin.

#include <gtest/gtest.h>

#include <cmath>

#include "../dynamics/patch_meshes.hpp"
#include "geometry/tessellate.hpp"
#include "validation/replay.hpp"

namespace vcontact::validation {
namespace {

using Eigen::Vector3d;
constexpr double kMm = 1e-3;

// Two 10 mm cube feet at x = ±20 mm (one mesh, two shells), or one of them alone, in the
// payload frame whose origin is midway between them.
geometry::Shape feet(bool left, bool right) {
  const geometry::TriangleMesh cube = geometry::tessellateBox(Vector3d::Constant(10 * kMm));
  std::vector<std::pair<geometry::TriangleMesh, Eigen::Isometry3d>> parts;
  if (left) parts.emplace_back(cube, test::placed(Vector3d(-20 * kMm, 0, 0)));
  if (right) parts.emplace_back(cube, test::placed(Vector3d(20 * kMm, 0, 0)));
  return test::meshShape(test::merged(parts), "feet");
}

// The feet spin about the vertical axis through the origin at ω while the part rocks about x
// and lifts: z(t) = 5 mm − d(t), tilt β(t) about y, so that at times the right foot leaves the
// plate and comes back.
Dataset spinningFeet(const geometry::Shape& payload, double omega, double tilt, std::size_t n) {
  Dataset ds;
  ds.payload = payload;
  ds.plate = geometry::HalfSpace{};
  ds.outputs = {"fx", "fy", "fz", "tx", "ty", "tz"};
  for (std::size_t i = 0; i < n; ++i) {
    Sample s;
    s.t = 1e-3 * static_cast<double>(i);
    const double beta = tilt * std::sin(2 * M_PI * 5 * s.t);
    s.X_BA.linear() = (Eigen::AngleAxisd(omega * s.t, Vector3d::UnitZ()) *
                       Eigen::AngleAxisd(beta, Vector3d::UnitY()))
                          .toRotationMatrix();
    s.X_BA.translation() = Vector3d(0, 0, 5 * kMm - 8e-6);
    s.w_BA = Vector3d(0, 0, omega);
    ds.samples.push_back(s);
  }
  return ds;
}

dynamics::Model frictionModel(bool bristle) {
  dynamics::Model m = dynamics::Model::withEffects(
      bristle ? std::vector<std::string>{"stiffness", "damping", "coulomb", "bristle"}
              : std::vector<std::string>{"stiffness", "coulomb"});
  m.setParameter("stiffness.kv", 5e12);
  m.setParameter("coulomb.mu", 0.3);
  return m;
}

TEST(ReplayPatches, SpinningFeetFeelTheFrictionCoupleOfTheirOwnSliding) {
  // Flat on the plate, spinning about the axis midway between the feet: each foot's centroid
  // slides at ω·20 mm (far above v_ε), so Coulomb friction μ f_n,i acts against it at a lever
  // of 20 mm: τ_z = −μ kv V · 20 mm in total. The two feet's joint centroid does not move,
  // so one lumped region would feel no friction at all.
  const double omega = 2.0, d = 8e-6, mu = 0.3, kv = 5e12;
  const Dataset ds = spinningFeet(feet(true, true), omega, 0.0, 20);
  Replayer replayer(ds);
  const Prediction p = replayer.run(frictionModel(false));
  const double V = 2 * 10 * kMm * 10 * kMm * d;
  for (Eigen::Index i = 0; i < p.wrench.rows(); ++i) {
    // 1e-9: the half-space clip of the boxes is exact; what is left is round-off.
    EXPECT_NEAR(p.wrench(i, 2) / (kv * V), 1.0, 1e-9);
    EXPECT_NEAR(p.wrench(i, 5) / (-mu * kv * V * 20 * kMm), 1.0, 1e-9);
    EXPECT_LT(p.wrench.row(i).head<2>().norm(), 1e-9 * kv * V) << "the two forces are a couple";
  }
}

TEST(ReplayPatches, FeetAreReplayedAsIfEachWereAlone) {
  // Rocking by ±1 mrad lifts each foot (20 mm × 1 mrad = 20 µm > 8 µm) in turn, so patches
  // vanish and come back while the other stays. Each patch carries its own bristle and is
  // reset when its foot lifts, exactly as a replay of that foot alone: the sums agree to
  // round-off of the wrench.
  const std::size_t n = 400;
  const dynamics::Model m = frictionModel(true);
  const Dataset db = spinningFeet(feet(true, true), 0.3, 1e-3, n);
  const Dataset dl = spinningFeet(feet(true, false), 0.3, 1e-3, n);
  const Dataset dr = spinningFeet(feet(false, true), 0.3, 1e-3, n);
  Replayer both(db), left(dl), right(dr);
  const Prediction pb = both.run(m), pl = left.run(m), pr = right.run(m);
  const Eigen::MatrixXd sum = pl.wrench + pr.wrench;
  int oneFoot = 0;
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(n); ++i) {
    const double scale = sum.row(i).head<3>().norm() + 1e-30;
    EXPECT_LT((pb.wrench.row(i) - sum.row(i)).head<3>().norm(), 1e-9 * scale) << "sample " << i;
    EXPECT_LT((pb.wrench.row(i) - sum.row(i)).tail<3>().norm(), 1e-9 * scale * 20 * kMm)
        << "sample " << i;
    oneFoot += (pl.wrench(i, 2) == 0.0) != (pr.wrench(i, 2) == 0.0);
  }
  EXPECT_GT(oneFoot, 40) << "the record must lift each foot for a while";
}

}  // namespace
}  // namespace vcontact::validation
