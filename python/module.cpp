// The extension module vcontact._vcontact: shapes, poses and contact queries here; models,
// scenarios and datasets in the other bind_*.cpp files. python/vcontact/__init__.py is the
// documented face of the package (docs/PYTHON.md).

#include <cmath>

#include "geometry/error.hpp"
#include "geometry/mesh_check.hpp"
#include "io/shape_spec.hpp"
#include "python/bindings.hpp"
#include "volume/contact.hpp"

namespace vcontact::python {
namespace {

// The mesh's vertices and faces as read-only NumPy arrays over the engine's own storage: no
// copy; each array keeps the mesh alive.
py::tuple meshArrays(const PyShape& s) {
  const auto* m = std::get_if<geometry::Mesh>(&s.shape);
  if (!m) throw InputError(geometry::describe(s.shape), "not a mesh");
  auto owner = py::capsule(new std::shared_ptr<const geometry::TriangleMesh>(m->mesh), [](void* p) {
    delete static_cast<std::shared_ptr<const geometry::TriangleMesh>*>(p);
  });
  const geometry::TriangleMesh& mesh = *m->mesh;
  py::array_t<double> v({mesh.vertices.rows(), Eigen::Index(3)}, mesh.vertices.data(), owner);
  py::array_t<int> f({mesh.triangles.rows(), Eigen::Index(3)}, mesh.triangles.data(), owner);
  py::detail::array_proxy(v.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  py::detail::array_proxy(f.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return py::make_tuple(v, f);
}

PyShape parsedShape(const std::string& text, bool repair, bool fillHoles) {
  io::MeshReadOptions options;
  options.repair = repair || fillHoles;
  options.repairOptions.fillHoles = fillHoles;
  io::ParsedShape p = io::parseShape(text, text, options);
  return {std::move(p.shape), std::move(p.warnings)};
}

// Face indices as read from any numeric array: integers, or floats that hold integers (a
// float 1.5 was truncated to 1 silently); a ValueError names the first one that is not.
geometry::Triangles faceIndices(const py::array& faces, py::ssize_t vertexCount,
                                const std::string& name) {
  const char kind = faces.dtype().kind();
  if (kind != 'i' && kind != 'u' && kind != 'f') {
    throw py::type_error(name + ": faces: expected an array of integer vertex indices");
  }
  const auto f = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(faces);
  if (f.ndim() != 2 || f.shape(1) != 3) throw InputError(name, "faces: expected an (m, 3) array");
  geometry::Triangles triangles(f.shape(0), 3);
  for (py::ssize_t i = 0; i < f.size(); ++i) {
    const double k = f.data()[i];
    const std::string at = " at face " + std::to_string(i / 3);
    if (!(k == std::floor(k))) {
      throw InputError(name, "faces: index " + std::to_string(k) + at + " is not an integer");
    }
    if (k < 0 || k >= static_cast<double>(vertexCount)) {
      throw InputError(name, "faces: index " + std::to_string(static_cast<long long>(k)) + at +
                                 " is not a vertex (0 to " + std::to_string(vertexCount - 1) + ")");
    }
    triangles.data()[i] = static_cast<int>(k);
  }
  return triangles;
}

// A mesh from arrays, checked (and optionally repaired) as a mesh file is.
PyShape meshFromArrays(const py::array_t<double, py::array::c_style | py::array::forcecast>& v,
                       const py::array& f, const std::string& name, bool repair, bool fillHoles) {
  if (v.ndim() != 2 || v.shape(1) != 3)
    throw InputError(name, "vertices: expected an (n, 3) array");
  geometry::TriangleMesh mesh;
  mesh.vertices = Eigen::Map<const geometry::Vertices>(v.data(), v.shape(0), 3);
  mesh.triangles = faceIndices(f, v.shape(0), name);
  std::vector<std::string> warnings;
  try {
    geometry::checkFinite(mesh);
    if (repair || fillHoles) {
      geometry::RepairOptions options;
      options.fillHoles = fillHoles;
      geometry::RepairResult r = geometry::repairMesh(mesh, options);
      mesh = std::move(r.mesh);
      warnings = std::move(r.changes);
    }
    const geometry::MeshCheckResult check = geometry::checkAndRepair(mesh);
    warnings.insert(warnings.end(), check.warnings.begin(), check.warnings.end());
  } catch (const InputError& e) {
    throw e.withSource(name);
  }
  return {geometry::Mesh{std::make_shared<const geometry::TriangleMesh>(std::move(mesh)), name},
          std::move(warnings)};
}

// depth=False leaves `fast`'s exact depth pass out (QueryOptions::depth): its regions' "depth"
// is then None (contactVolumeDict), as "relative_error" is where a method has none.
py::dict contactDict(const PyShape& a, const py::object& X_WA, const PyShape& b,
                     const py::object& X_WB, const std::optional<std::string>& method, bool depth) {
  volume::QueryOptions options;
  if (method) options.method = volume::parseMethod(*method);
  options.depth = depth ? volume::DepthMode::kDeepest : volume::DepthMode::kSkip;
  const volume::ContactPatches c =
      volume::computeContact(a.shape, toPose(X_WA, "X_WA"), b.shape, toPose(X_WB, "X_WB"), options);
  py::list patches;
  for (const auto& p : c.patches) patches.append(contactVolumeDict(p));
  py::dict d;
  d["in_contact"] = c.inContact();
  d["aggregate"] = contactVolumeDict(c.aggregate);
  d["patches"] = patches;
  return d;
}

void bindShapes(py::module_& m) {
  py::class_<PyShape>(m, "Shape", "A body's shape in its own frame (README, \"Shapes\").")
      .def_property_readonly("kind", [](const PyShape& s) { return geometry::shapeKind(s.shape); })
      .def_property_readonly("description",
                             [](const PyShape& s) { return geometry::describe(s.shape); })
      .def_readonly("warnings", &PyShape::warnings, "repairs and doubts from reading it")
      .def_property_readonly("arrays", &meshArrays,
                             "(vertices (n, 3) m, faces (m, 3)) of a mesh, read-only, no copy")
      .def("__repr__",
           [](const PyShape& s) { return "<vcontact.Shape " + geometry::describe(s.shape) + ">"; });
  m.def("shape", &parsedShape, py::arg("text"), py::arg("repair") = false,
        py::arg("fill_holes") = false, "A shape from its text: sphere:R, box:X,Y,Z, FILE@mm, ...");
  m.def("mesh_from_arrays", &meshFromArrays, py::arg("vertices"), py::arg("faces"),
        py::arg("name") = "mesh", py::arg("repair") = false, py::arg("fill_holes") = false);
  m.def(
      "pose_matrix", [](const py::object& pose) { return poseMatrix(toPose(pose, "pose")); },
      py::arg("pose"), "The 4x4 matrix of any pose form contact() accepts.");
  m.def("contact", &contactDict, py::arg("a"), py::arg("X_WA"), py::arg("b"), py::arg("X_WB"),
        py::arg("method") = py::none(), py::arg("depth") = false);
}

}  // namespace
}  // namespace vcontact::python

PYBIND11_MODULE(_vcontact, m) {
  namespace vp = vcontact::python;
  m.doc() = "vcontact engine bindings; use the vcontact package (docs/PYTHON.md).";
  static pybind11::exception<vcontact::InputError> inputError(m, "InputError", PyExc_ValueError);
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const vcontact::InputError& e) {
      inputError(e.what());
    }
  });
  vp::bindShapes(m);
  vp::bindModel(m);
  vp::bindScenario(m);
  vp::bindDataset(m);
  vp::bindBatch(m);
}
