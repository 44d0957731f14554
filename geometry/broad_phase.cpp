#include "geometry/broad_phase.hpp"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <cassert>
#include <variant>

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

namespace {

struct LocalBounds {
  std::optional<Aabb> operator()(const Sphere& s) const {
    return centred(Eigen::Vector3d::Constant(s.radius));
  }
  std::optional<Aabb> operator()(const Cylinder& c) const {
    return centred(Eigen::Vector3d(c.radius, c.radius, 0.5 * c.length));
  }
  std::optional<Aabb> operator()(const Box& b) const { return centred(0.5 * b.size); }
  std::optional<Aabb> operator()(const HalfSpace&) const { return std::nullopt; }
  std::optional<Aabb> operator()(const Mesh& m) const { return bounds(*m.mesh); }
  static Aabb centred(const Eigen::Vector3d& half) { return {-half, half}; }
};

// Relative growth of placedBounds: rounding of X·c and |R|·h is a few ε of the sizes involved.
constexpr double kPlacedGrowth = 1e-9;

}  // namespace

std::optional<Aabb> localBounds(const Shape& shape) { return std::visit(LocalBounds{}, shape); }

Aabb placedBounds(const Aabb& local, const Eigen::Isometry3d& X_WS) {
  const Eigen::Vector3d c = X_WS * (0.5 * (local.min + local.max));
  const Eigen::Vector3d h = X_WS.linear().cwiseAbs() * (0.5 * local.size());
  const double grow = kPlacedGrowth * (c.cwiseAbs().maxCoeff() + h.maxCoeff());
  const Eigen::Vector3d half = h + Eigen::Vector3d::Constant(grow);
  return {c - half, c + half};
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
