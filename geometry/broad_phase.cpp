#include "geometry/broad_phase.hpp"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <cassert>

namespace vcontact::geometry {

namespace {

/// A body's box as an FCL box shape of the same size centred on it (its AABB is the box).
struct Body {
  std::shared_ptr<fcl::Boxd> shape;
  std::unique_ptr<fcl::CollisionObjectd> object;

  void place(const Aabb& box_W) {
    assert((box_W.min.array() <= box_W.max.array()).all());
    shape->side = box_W.size();
    shape->computeLocalAABB();
    object->setTransform(Eigen::Matrix3d::Identity(), 0.5 * (box_W.min + box_W.max));
    object->computeAABB();
  }
};

bool recordPair(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
  const int i = static_cast<int>(reinterpret_cast<std::intptr_t>(a->getUserData()));
  const int j = static_cast<int>(reinterpret_cast<std::intptr_t>(b->getUserData()));
  static_cast<std::vector<std::pair<int, int>>*>(data)->emplace_back(std::min(i, j),
                                                                     std::max(i, j));
  return false;  // keep going
}

}  // namespace

struct BroadPhase::Impl {
  fcl::DynamicAABBTreeCollisionManagerd manager;
  std::vector<Body> bodies;  // index = id
};

BroadPhase::BroadPhase() : impl_(std::make_unique<Impl>()) {}
BroadPhase::~BroadPhase() = default;

int BroadPhase::add(const Aabb& box_W) {
  const int id = static_cast<int>(impl_->bodies.size());
  Body body;
  body.shape = std::make_shared<fcl::Boxd>(box_W.size());
  body.object = std::make_unique<fcl::CollisionObjectd>(body.shape);
  body.object->setUserData(reinterpret_cast<void*>(static_cast<std::intptr_t>(id)));
  body.place(box_W);
  impl_->manager.registerObject(body.object.get());
  impl_->bodies.push_back(std::move(body));
  return id;
}

void BroadPhase::update(int id, const Aabb& box_W) {
  Body& body = impl_->bodies.at(static_cast<std::size_t>(id));
  body.place(box_W);
  impl_->manager.update(body.object.get());
}

std::vector<std::pair<int, int>> BroadPhase::overlappingPairs() const {
  std::vector<std::pair<int, int>> pairs;
  impl_->manager.collide(&pairs, recordPair);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

Aabb worldBounds(const TriangleMesh& mesh, const Eigen::Isometry3d& X_WM) {
  Aabb box{Eigen::Vector3d::Constant(INFINITY), Eigen::Vector3d::Constant(-INFINITY)};
  for (Eigen::Index i = 0; i < mesh.vertexCount(); ++i) {
    const Eigen::Vector3d p = X_WM * mesh.vertex(i);
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

}  // namespace vcontact::geometry
