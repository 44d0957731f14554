// The exact depth pass (volume/depth/deepest_column.cpp) after its speed-ups against the pass of
// 89ea7e6 (depth/deepest_column_reference.hpp), on the boundary segments of real queries: the two
// must give the same depth bit for bit (both take the max of the same candidate values; the new one
// only skips candidates that the exact formulas reject anyway and evaluates shared vertex
// columns once). Cases: cad_tray_drop's tray resting flat on its fixture and the upper tray on
// the tray's rim (thin, wide regions: the case the speed-ups are for), moved by small random
// motions, and two spheres whose lens has its poles in the region; bin_of_ten's resting pairs and
// the peg of peg_jam in its bore, at their poses and moved at random; synthetic thin conical
// shells, steep along the columns (the detrended bounds' case).

#include "volume/depth/deepest_column.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "deepest_column_reference.hpp"
#include "geometry/tessellate.hpp"
#include "io/mesh_io.hpp"
#include "scenario_mesh.hpp"
#include "volume/contact.hpp"
#include "volume/fast/intersector.hpp"
#include "volume/fast/surface_integration.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

Isometry3d pose(const Vector3d& p, const Quaterniond& q) {
  Isometry3d X = Isometry3d::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = p;
  return X;
}

/// A small rigid motion: translation up to `reach` along each axis, rotation up to reach / 0.05
/// rad (a point 50 mm from the origin moves by about `reach`).
Isometry3d jitter(std::mt19937& rng, double reach) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vector3d axis = Vector3d(u(rng), u(rng), u(rng)).normalized();
  Isometry3d X = Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(u(rng) * reach / 0.05, axis).toRotationMatrix();
  X.translation() = reach * Vector3d(u(rng), u(rng), u(rng));
  return X;
}

/// The query's depth pass replayed through the reference and through a fresh ColumnDepth; with
/// `mayMiss`, a pose out of contact is passed over. Returns whether the pair was in contact.
bool expectSameDepth(const geometry::Shape& a, const Isometry3d& X_WA, const geometry::Shape& b,
                     const Isometry3d& X_WB, const std::string& what, bool mayMiss = false) {
  SCOPED_TRACE(what);
  const ContactPatches c = fastContact(a, X_WA, b, X_WB, nullptr, true);
  if (mayMiss && !c.aggregate.inContact()) return false;
  EXPECT_TRUE(c.aggregate.inContact());
  if (!c.aggregate.inContact()) return false;
  const ColumnDepth& pass = internal::lastDepthPass();
  EXPECT_FALSE(pass.inputs().empty());
  test::ReferenceColumnDepth reference;
  ColumnDepth fresh;
  for (const ColumnDepth::Input& in : pass.inputs()) {
    reference.add(in.key, in.n_f, in.p, in.q);
    fresh.add(in.key, in.n_f, in.p, in.q);
  }
  const ColumnDepth::Arguments& args = pass.lastArguments();
  const double expected = reference.deepest(args.n, args.o, args.scale);
  EXPECT_GT(expected, 0.0);
  EXPECT_EQ(fresh.deepest(args.n, args.o, args.scale), expected);
  // One patch: the aggregate's depth is that pass's.
  if (c.patches.size() <= 1) {
    EXPECT_EQ(c.aggregate.depth, expected);
  }
  return true;
}

// Poses from `vcontact simulate` of cad_tray_drop.json with "integrator": "discrete",
// "step": 0.001, "duration": 0.2 (bodies.csv at 0.2 s; the fixture at the origin).
TEST(DepthPass, EqualsTheReferenceOnTheRestingTrays) {
  const geometry::Shape fixture = vcontact::test::scenarioMesh("fixture_10k.stl");
  const geometry::Shape tray = vcontact::test::scenarioMesh("tray_10k.stl");
  const Isometry3d tray0 = pose(
      {-0.00014387366508314872, 6.0918756562598135e-05, -1.8125896664687724e-08},
      {0.9999995904400925, 8.728725639001793e-10, 1.5492801399966383e-07, -0.0009050522766467364});
  const Isometry3d upper0 = pose(
      {0.00022884139704104997, 4.758616037277994e-06, 0.01999974070521958},
      {0.9999998766135039, -6.02758003025285e-08, 3.4593768342127e-05, -0.0004955564998365197});
  expectSameDepth(tray, tray0, fixture, Isometry3d::Identity(), "tray on fixture at rest");
  expectSameDepth(tray, upper0, tray, tray0, "upper tray on tray at rest");
  std::mt19937 rng(18);
  for (int k = 0; k < 4; ++k) {
    // Motions of 0.2 µm (a step's creep at rest) to 20 µm (the landing's steps): the tray
    // stays on the block, sunk by ~0.04 µm more or less, tilted by up to 4e-4 rad.
    const double reach = k % 2 == 0 ? 2e-7 : 2e-6;
    const Isometry3d J = jitter(rng, reach);
    Isometry3d sunk = J * tray0;
    sunk.translation().z() = tray0.translation().z() - 5e-8;
    expectSameDepth(tray, sunk, fixture, Isometry3d::Identity(),
                    "tray on fixture, moved " + std::to_string(k));
    Isometry3d upper = jitter(rng, reach) * upper0;
    upper.translation().z() = upper0.translation().z() - 1e-7;
    expectSameDepth(tray, upper, tray, tray0, "upper tray, moved " + std::to_string(k));
  }
}

/// The trays' poses at output times of the landing in a discrete run (`vcontact simulate` of
/// cad_tray_drop.json with "integrator": "discrete", "step": 0.001, "impacts": "implicit";
/// bodies.csv, the fixture at the origin).
struct LandingPose {
  double t;
  Isometry3d tray, upper;
};

std::vector<LandingPose> landingPoses() {
  return {
      {0.016,
       pose({0.0009979744303743856, 4.5923662391691725e-09, 0.005241153221232744},
            {0.9999984802626799, 1.698587534325493e-07, 2.261015451739207e-05,
             0.0017432616219505142}),
       pose({0.001, 0, 0.025744319999999998}, {0.9999984769132877, 0, 0, 0.0017453283658983084})},
      {0.021,
       pose({0.0006440304645903746, -5.197311701562892e-06, 0.004962280136914345},
            {0.9999991166429595, -6.324376251797711e-05, 0.0003301706926580324,
             0.0012859630013470273}),
       pose({0.001, 0, 0.024836894999999994}, {0.9999984769132877, 0, 0, 0.0017453283658983084})},
      {0.023,
       pose({0.0005185294762385237, -7.685769677853404e-06, 0.0046566288827895866},
            {0.9999984787135198, -9.768958964793837e-05, 0.0012961931762469861,
             0.001163146869537796}),
       pose({0.0009135852689755031, -1.158018440638184e-06, 0.024588192491279165},
            {0.9999982165735745, -3.405892280885978e-05, 0.0009660648604330463,
             0.0016224698288893693})},
      {0.025,
       pose({0.00037294675810169327, -1.2687652757887584e-05, 0.004310874440216877},
            {0.9999966214095717, -0.00017119896726579552, 0.0023846228206200384,
             0.0010205069126165956}),
       pose({0.0008120488984091372, -3.313780931799227e-06, 0.024322959406909136},
            {0.9999967885994382, -0.00010709125744425245, 0.0020546344762922726,
             0.0014797970948621467})},
      {0.040,
       pose({-0.0001526821012327092, 1.3467717192809325e-05, 0.0013418372574702901},
            {0.9999898696698029, -1.4135425619868628e-05, 0.004480074779240866,
             -0.0004350723305797156}),
       pose({0.0001973315436698374, -3.0159427087643512e-06, 0.021399070326594983},
            {0.9999853886467781, -0.00021122585555302548, 0.005398762678371694,
             0.00017674312672806})},
      {0.046,
       pose({-0.00014499835289114537, 4.520102982333184e-05, -2.040044183927378e-05},
            {0.9999968703234142, 0.0005111622288399947, 0.0022537412450730865,
             -0.0009584920201942377}),
       pose({0.00010564524914981902, 1.3009594801399806e-05, 0.019851604493951333},
            {0.9999915436469348, 0.00026168272669832175, 0.004081679492471393,
             -0.00042900966400580574})},
      {0.049,
       pose({-0.00014502661225047686, 4.52071756458191e-05, 8.839530017605308e-05},
            {0.9999970140003911, 0.0005042708231006759, 0.002190659022737358,
             -0.0009584958449701496}),
       pose({0.00010392539624388897, 1.3268832158554571e-05, 0.020057758960767533},
            {0.9999918226449255, 0.0002555109725461265, 0.0040131370652179334,
             -0.0004290551463692897})},
  };
}

// The landing (issue 18): the tray's pins in the chamfers and its base reaching the block, the
// upper tray tilted on the rim (0.1-0.25 mm deep, columns whose lengths vary over the region by
// as much as the deepest: the regions where a cell's bound comes from the heights of its part
// of each segment and face, not of the whole), each pose as it is and moved by 2 um.
TEST(DepthPass, EqualsTheReferenceOnTheLandingTrays) {
  const geometry::Shape fixture = vcontact::test::scenarioMesh("fixture_10k.stl");
  const geometry::Shape tray = vcontact::test::scenarioMesh("tray_10k.stl");
  std::mt19937 rng(21);
  int trayPoses = 0, upperPoses = 0;
  for (const LandingPose& p : landingPoses()) {
    const std::string t = " at " + std::to_string(p.t) + " s";
    for (const bool moved : {false, true}) {
      const Isometry3d J = moved ? jitter(rng, 2e-6) : Isometry3d::Identity();
      trayPoses += expectSameDepth(tray, J * p.tray, fixture, Isometry3d::Identity(),
                                   "tray on fixture" + t, true);
      upperPoses += expectSameDepth(tray, J * p.upper, tray, p.tray, "upper tray" + t, true);
    }
  }
  // In contact at every pose but the upper tray's first (t = 0.016 s): not vacuous.
  EXPECT_GE(trayPoses, 12);
  EXPECT_GE(upperPoses, 10);
}

// A lens of two 10k spheres (its poles in the region, where slivers of faces meet).
TEST(DepthPass, EqualsTheReferenceOnALens) {
  const geometry::Shape s = geometry::Mesh{
      std::make_shared<const geometry::TriangleMesh>(geometry::tessellateSphere(0.01, 100, 51)),
      "sphere"};
  std::mt19937 rng(7);
  for (const double overlap : {2e-6, 2e-4, 2e-3}) {
    Isometry3d X_WA = Isometry3d::Identity();
    X_WA.translation() = Vector3d(0, 0, 0.02 - overlap);
    expectSameDepth(s, X_WA, s, Isometry3d::Identity(),
                    "poles aligned, overlap " + std::to_string(overlap));
    expectSameDepth(s, jitter(rng, overlap / 4) * X_WA, s, Isometry3d::Identity(),
                    "turned, overlap " + std::to_string(overlap));
  }
}

/// The boundary of a thin shell on a cone, as the depth pass takes it: bottom faces on
/// z = slope (r − r0) and top faces d(r, θ) above them, over r in [r0, r0 + 0.6 mm] and a sector
/// of 1.5 rad, each triangle's three edges with its outward unit normal (up for the top faces,
/// down for the bottom ones). Seen along z tilted by `tilt` the heights over one grid cell vary
/// by the slope times its width, several times the depth (the pins of cad_tray_drop in their
/// chamfers): the case of the detrended bounds (volume/depth/deepest_column_trend.cpp).
template <class Pass>
void addConicalShell(Pass& pass, double slope, int rings, int sectors) {
  const double r0 = 2.4e-3, width = 6e-4, sector = 1.5;
  const auto point = [&](int i, int j, bool top) {
    const double r = r0 + width * i / rings, th = sector * j / sectors;
    // a depth of about 50 µm varying across the sector and the width, so the deepest column
    // is not everywhere at once (and not at a vertex of the grid of rings and sectors)
    const double d = top ? 5e-5 * (1.0 + 0.2 * std::sin(3.1 * th + 0.4) * (r - r0) / width) : 0.0;
    return Vector3d(r * std::cos(th), r * std::sin(th), slope * (r - r0) + d);
  };
  std::uint64_t face = 0;
  for (const bool top : {true, false}) {
    for (int i = 0; i < rings; ++i) {
      for (int j = 0; j < sectors; ++j) {
        const Vector3d p00 = point(i, j, top), p10 = point(i + 1, j, top);
        const Vector3d p01 = point(i, j + 1, top), p11 = point(i + 1, j + 1, top);
        for (const auto& tri :
             {std::array<Vector3d, 3>{p00, p10, p11}, std::array<Vector3d, 3>{p00, p11, p01}}) {
          Vector3d n_f = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalized();
          if ((n_f.z() > 0) != top) n_f = -n_f;
          const std::uint64_t key = (std::uint64_t{top ? 1u : 0u} << 32) | face++;
          for (int k = 0; k < 3; ++k) pass.add(key, n_f, tri[k], tri[(k + 1) % 3]);
        }
      }
    }
  }
}

// Thin conical shells of slopes 0.5 to 3 seen along z and along a direction tilted by 0.3 rad,
// coarsely and finely tessellated (the fine ones take the blocks of
// depth/deepest_column_bounds.cpp).
TEST(DepthPass, EqualsTheReferenceOnSteepThinShells) {
  int cases = 0;
  for (const double slope : {0.5, 1.0, 3.0}) {
    for (const double tilt : {0.0, 0.3}) {
      for (const auto& [rings, sectors] : {std::pair{6, 30}, std::pair{14, 60}}) {
        SCOPED_TRACE("slope " + std::to_string(slope) + ", tilt " + std::to_string(tilt) +
                     ", rings " + std::to_string(rings));
        test::ReferenceColumnDepth reference;
        ColumnDepth pass;
        addConicalShell(reference, slope, rings, sectors);
        addConicalShell(pass, slope, rings, sectors);
        const Vector3d n(std::sin(tilt), 0.0, std::cos(tilt)), o(2.4e-3, 1e-3, 0.0);
        const double expected = reference.deepest(n, o, 4e-3);
        // the shell's thickness along n: about 50 µm, more where the columns run obliquely
        EXPECT_GT(expected, 4e-5);
        EXPECT_EQ(pass.deepest(n, o, 4e-3), expected);
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, 12);
}

struct PartPose {
  const char* name;
  Vector3d p;
  Quaterniond q;
};

/// bin_of_ten's parts at rest: bodies.csv at 0.5 s of `vcontact simulate
/// assets/scenarios/bin_of_ten.json` (the bin fixed at the origin).
const PartPose kBinParts[] = {
    {"rounded_block",
     {-0.04000026531531976, -0.01998682527378496, 0.00699770588159635},
     {0.9961356763186265, -0.0008937303939475272, 0.00013969167248214655, 0.08782309546726426}},
    {"washer",
     {-0.003911283902915021, -0.021910225878803816, 0.0024999902326917306},
     {0.9999999990339533, 8.722295739306364e-11, -9.229784795380895e-11, 4.395558474237831e-05}},
    {"hex_nut",
     {0.03, -0.02, 0.0049991638535073725},
     {0.9914448613738104, -1.8790202554399728e-18, 1.0696257247022758e-18, 0.13052619222005163}},
    {"bored_block",
     {0.03802019414865424, 0.018028298974820042, 0.006999982672682424},
     {0.9847570168550289, -5.416216681585549e-07, -6.270432203590816e-08, -0.1739356713112262}},
    {"roller",
     {-0.035, 0.02, 0.007996505657745326},
     {0.7071067811865475, 0.7071067811865476, -6.035438128170067e-18, 6.035438128170318e-18}},
    {"ball",
     {-0.003913445095579346, -0.021912271542863234, 0.012104714147469445},
     {0.9952600584784971, 0.06887677199884638, -0.06864998984980361, 0.0007649640640880475}},
    {"torus",
     {-0.037664831319631005, -0.016439418817142195, 0.017788647233799523},
     {0.9997935758960366, -0.018394697317897047, 0.008262481935916407, 0.0024843711191413686}},
    {"capsule",
     {0.0076389502098859995, 0.001844491091483413, 0.006984815790308164},
     {0.7045021192801817, -0.16903604109957598, 0.6866052845772459, -0.060636325166637105}},
    {"frustum",
     {0.03693186741882298, 0.028459175715658837, 0.022999930113310463},
     {0.9987577740334381, -7.221221956861161e-06, 1.6821487382656007e-06, -0.04982879441443575}},
    {"shaft",
     {-1.0404984357088752e-05, 0.018848867837862583, 0.013999988070722424},
     {2.4789128197303798e-11, 0.9999999993379977, 3.638687484467339e-05, 3.8868210994108875e-12}},
};

// The eleven pairs of the resting bin in contact at 0.5 s (their pair files' depth > 0): parts
// flat on the floor (a box's face on the bin's: the flat, wide regions), a ball in a washer's
// bore, a torus on a rounded block, a frustum on a bored block, a capsule against a shaft.
TEST(DepthPass, EqualsTheReferenceOnTheRestingBin) {
  std::map<std::string, std::pair<geometry::Shape, Isometry3d>> parts;
  parts.emplace("bin", std::pair(vcontact::test::scenarioMesh("bin/bin.stl"),
                                 Isometry3d(Isometry3d::Identity())));
  for (const PartPose& part : kBinParts) {
    parts.emplace(part.name, std::pair(vcontact::test::scenarioMesh(std::string("bin/part_") +
                                                                    part.name + ".stl"),
                                       pose(part.p, part.q)));
  }
  const std::pair<const char*, const char*> pairs[] = {
      {"ball", "washer"},         {"bored_block", "bin"}, {"capsule", "bin"},
      {"frustum", "bored_block"}, {"hex_nut", "bin"},     {"roller", "bin"},
      {"rounded_block", "bin"},   {"shaft", "bin"},       {"shaft", "capsule"},
      {"torus", "rounded_block"}, {"washer", "bin"}};
  std::mt19937 rng(10);
  int moved = 0;
  for (const auto& [a, b] : pairs) {
    const auto& [shapeA, X_WA] = parts.at(a);
    const auto& [shapeB, X_WB] = parts.at(b);
    const std::string name = std::string(a) + "-" + b;
    expectSameDepth(shapeA, X_WA, shapeB, X_WB, name + " at rest");
    // A step's creep at rest and a landing's step (0.2 and 2 um), pressed in by 0.1 um.
    for (const double reach : {2e-7, 2e-6}) {
      Isometry3d X = jitter(rng, reach) * X_WA;
      X.translation().z() -= 1e-7;
      moved += expectSameDepth(shapeA, X, shapeB, X_WB, name + " moved", true);
    }
  }
  EXPECT_GE(moved, 15);  // 18 of the 22 touch here: the comparison is not vacuous
}

// The peg of peg_jam in its bore (peg_patches_test's jammed pose, two bearing patches, and the
// first contact, one) under random motions of 5-50 um and up to 1 mrad (jitter): crescents on
// the bore's facets, some poses with the tip's corner through a facet, some out of contact.
TEST(DepthPass, EqualsTheReferenceOnThePegInItsBore) {
  const geometry::Shape peg = vcontact::test::scenarioMesh("peg_d10.stl");
  const geometry::Shape block = vcontact::test::scenarioMesh("block_hole_d10.stl");
  const Isometry3d jammed = pose({0.0, -0.0010936879585314594, 0.012002743575543097},
                                 {0.9991559436078984, 0.0410779789304455, 0.0, 0.0});
  const Isometry3d first = pose({0.0, -0.001204810798351416, 0.012562245095595842},
                                {0.9990026234096686, 0.04465152204124483, 0.0, 0.0});
  expectSameDepth(peg, jammed, block, Isometry3d::Identity(), "jammed");
  expectSameDepth(peg, first, block, Isometry3d::Identity(), "first contact");
  std::mt19937 rng(18);
  int inContact = 0;
  for (int k = 0; k < 24; ++k) {
    const double reach = k % 3 == 0 ? 5e-6 : (k % 3 == 1 ? 2e-5 : 5e-5);
    const Isometry3d& X = k % 2 == 0 ? jammed : first;
    inContact += expectSameDepth(peg, jitter(rng, reach) * X, block, Isometry3d::Identity(),
                                 "moved " + std::to_string(k), true);
  }
  EXPECT_GE(inContact, 18);  // all 24 touch here: the comparison is not vacuous
}

}  // namespace
}  // namespace vcontact::volume
