// Simbody's elastic foundation on two copies of one triangle mesh (benchmarks/simbody_bench.cpp).
// Compiled as C++17: Simbody 3.7's headers do not compile as C++20 (their index types' operator==
// becomes ambiguous with C++20's reversed candidates), so no vcontact header is included here
// and no Simbody type crosses the seam (simbody_pair.hpp).

#include "simbody_pair.hpp"

#include <Simbody.h>

namespace vcontact::bench {

/// B fixed to Ground, A on a Free mobilizer; both meshes in one contact set with the elastic
/// foundation at stiffness k on each, no friction, no dissipation (A at rest).
struct SimbodyPair::Impl {
  Impl(const std::vector<double>& vertices, const std::vector<int>& triangles, double k)
      : matter(system), contacts(system), forces(system) {
    SimTK::PolygonalMesh polygons;
    for (std::size_t i = 0; i + 2 < vertices.size(); i += 3)
      polygons.addVertex(SimTK::Vec3(vertices[i], vertices[i + 1], vertices[i + 2]));
    for (std::size_t f = 0; f + 2 < triangles.size(); f += 3) {
      SimTK::Array_<int> face(3);
      for (int c = 0; c < 3; ++c) face[c] = triangles[f + static_cast<std::size_t>(c)];
      polygons.addFace(face);
    }
    const SimTK::ContactSetIndex set = contacts.createContactSet();
    const SimTK::Body::Rigid body(SimTK::MassProperties(1.0, SimTK::Vec3(0), SimTK::Inertia(1)));
    ball =
        SimTK::MobilizedBody::Free(matter.Ground(), SimTK::Transform(), body, SimTK::Transform());
    contacts.addBody(set, matter.Ground(), SimTK::ContactGeometry::TriangleMesh(polygons),
                     SimTK::Transform());
    contacts.addBody(set, ball, SimTK::ContactGeometry::TriangleMesh(polygons), SimTK::Transform());
    SimTK::ElasticFoundationForce ef(forces, contacts, set);
    for (int s = 0; s < 2; ++s)
      ef.setBodyParameters(SimTK::ContactSurfaceIndex(s), k, 0.0, 0.0, 0.0, 0.0);
    state = system.realizeTopology();
  }
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter;
  SimTK::GeneralContactSubsystem contacts;
  SimTK::GeneralForceSubsystem forces;
  SimTK::MobilizedBody::Free ball;
  SimTK::State state;
};

SimbodyPair::SimbodyPair(const std::vector<double>& vertices, const std::vector<int>& triangles,
                         double k)
    : impl_(std::make_unique<Impl>(vertices, triangles, k)) {}

SimbodyPair::~SimbodyPair() = default;

std::array<double, 3> SimbodyPair::force(const std::array<double, 9>& R_WA,
                                         const std::array<double, 3>& p_WA) {
  SimTK::Mat33 R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = R_WA[static_cast<std::size_t>(3 * r + c)];
  const SimTK::Transform X_WA(SimTK::Rotation(R, true), SimTK::Vec3(p_WA[0], p_WA[1], p_WA[2]));
  impl_->ball.setQToFitTransform(impl_->state, X_WA);  // invalidates Position and above
  impl_->system.realize(impl_->state, SimTK::Stage::Dynamics);
  const SimTK::Vec3 f = impl_->system.getRigidBodyForces(
      impl_->state, SimTK::Stage::Dynamics)[impl_->ball.getMobilizedBodyIndex()][1];
  return {f[0], f[1], f[2]};
}

}  // namespace vcontact::bench
