#pragma once
// A bundled scenario mesh (assets/scenarios/meshes/NAME) as a mesh shape, for the volume tests
// that replay the simulations' poses.

#include <memory>
#include <string>

#include "geometry/primitives.hpp"
#include "io/mesh_io.hpp"

namespace vcontact::test {

inline geometry::Shape scenarioMesh(const std::string& name) {
  const std::string path = std::string(VCONTACT_ASSETS_DIR) + "/scenarios/meshes/" + name;
  return geometry::Mesh{std::make_shared<const geometry::TriangleMesh>(io::readMesh(path).mesh),
                        name};
}

}  // namespace vcontact::test
