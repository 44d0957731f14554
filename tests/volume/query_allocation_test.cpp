// Allocations of the fast mesh–mesh query in a simulation's steady state (issue 18, item 4): once
// a thread's scratch memory and a pair's cache have grown to the size of the contact, a query
// along a path of nearby poses allocates nothing but its result (ContactPatches::patches, one
// vector per query), with or without the depth pass. This binary replaces the global operator
// new to count the allocations; nothing else runs in it.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <new>

#include "geometry/tessellate.hpp"
#include "volume/contact.hpp"
#include "volume/fast/surface_integration.hpp"

namespace {
std::atomic<long> gAllocations{0};
}

void* operator new(std::size_t size) {
  ++gAllocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

// Two 10k-triangle spheres 0.2 mm into each other, A moving by 0.1 µm a query (a resting
// step's creep) over 40 queries, then back: the first pass sizes every buffer, the second
// must not allocate beyond the result's one vector.
TEST(QueryAllocations, NoneBeyondTheResultOnceWarm) {
  const geometry::Shape s = geometry::Mesh{
      std::make_shared<const geometry::TriangleMesh>(geometry::tessellateSphere(0.01, 100, 51)),
      "sphere"};
  Isometry3d X_WA = Isometry3d::Identity();
  X_WA.linear() = Eigen::AngleAxisd(0.3, Vector3d(1, 2, 0).normalized()).toRotationMatrix();
  X_WA.translation() = Vector3d(0.0013, -0.0007, 0.0198);
  const auto at = [&](int k) {
    Isometry3d X = X_WA;
    X.translation() += Vector3d(1e-7 * k, 5e-8 * k, 0.0);
    return X;
  };
  for (const bool deepest : {false, true}) {
    SCOPED_TRACE(deepest ? "with the depth pass" : "without the depth pass");
    MeshMeshCache cache;
    for (int k = 0; k < 40; ++k) fastContact(s, at(k), s, Isometry3d::Identity(), &cache, deepest);
    long most = 0;
    for (int k = 39; k >= 0; --k) {
      const long before = gAllocations.load();
      const ContactPatches c = fastContact(s, at(k), s, Isometry3d::Identity(), &cache, deepest);
      most = std::max(most, gAllocations.load() - before);
      ASSERT_TRUE(c.aggregate.inContact());
      ASSERT_EQ(c.patches.size(), 1u);  // the one allocation: the result's patch vector
    }
    EXPECT_EQ(most, 1);
    EXPECT_GT(cache.reuses, 40);  // the path stays within the cache's reach
  }
}

}  // namespace
}  // namespace vcontact::volume
