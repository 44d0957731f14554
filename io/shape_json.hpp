#pragma once
// Shapes as JSON objects, shared by the dataset, scenario and other JSON readers:
//   {"shape": "sphere", "radius": R}
//   {"shape": "cylinder", "radius": R, "length": L}
//   {"shape": "box", "size": [X, Y, Z]}
//   {"shape": "halfspace"}
//   {"mesh": "part.stl", "scale": 0.001}     (path relative to the JSON file's folder;
//                                             "scale" may be a unit name: "mm", "in")
//   {"mesh": "part.stl", "repair": true}      (repairs the mesh: geometry/mesh_repair.hpp)

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "geometry/primitives.hpp"

namespace vcontact::io {

struct JsonShape {
  geometry::Shape shape;
  std::vector<std::string> warnings;  ///< mesh repairs
};

/// @param where   names the place in messages, e.g. "rig.json: payload"
/// @param baseDir folder that relative mesh paths are resolved against
/// @throws InputError naming `where` and what was expected
JsonShape parseShapeJson(const nlohmann::json& j, const std::string& where,
                         const std::string& baseDir);

/// The JSON object of a primitive shape (the inverse of parseShapeJson).
/// @throws InputError naming `which` for a mesh, which has no file to name
nlohmann::json shapeJson(const geometry::Shape& shape, const std::string& which);

/// A required finite number member; throws InputError naming `where` and the key.
double requireNumber(const nlohmann::json& j, const std::string& key, const std::string& where);

}  // namespace vcontact::io
