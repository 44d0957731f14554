// vcontact.Model: a force model (docs/MODEL.md) from a model file or a dict.

#include "dynamics/model.hpp"
#include "formats/model_file.hpp"
#include "geometry/error.hpp"
#include "io/json_file.hpp"
#include "python/bindings.hpp"

namespace vcontact::python {
namespace {

py::dict wrenchDict(const dynamics::Model& model, const dynamics::ContactResult& r) {
  py::dict shares;
  const auto ids = model.effectIds();
  for (std::size_t i = 0; i < ids.size() && i < r.shares.size(); ++i) {
    py::dict s;
    s["force"] = Eigen::Vector3d(r.shares[i].f_W);
    s["torque"] = Eigen::Vector3d(r.shares[i].tau_W);
    shares[py::str(ids[i])] = s;
  }
  py::dict d;
  d["force"] = Eigen::Vector3d(r.wrench.f_W);
  d["torque"] = Eigen::Vector3d(r.wrench.tau_W);
  d["f_n"] = r.f_n;
  d["s"] = r.s;
  d["mu_max"] = r.mu_max;
  d["shares"] = shares;
  return d;
}

// The wrench on body A at the contact centroid for the relative motion (v_c, ω) of A against
// B there (MODEL.md §2), from the zero pair state (no bristle deflection, no dwell).
py::dict wrench(const dynamics::Model& model, const py::dict& contact, const Eigen::Vector3d& v_c,
                const Eigen::Vector3d& w) {
  const volume::ContactVolume cv = contactVolumeFrom(contact);
  dynamics::RelativeMotion motion;
  motion.v_c_W = v_c;
  motion.w_W = w;
  return wrenchDict(model, model.evaluate(cv, motion, dynamics::PairState{}));
}

// Parsed as a model file is (io/json_file.hpp): a repeated key is refused, not kept.
dynamics::Model fromJsonText(const std::string& text, const std::string& source) {
  return formats::modelFromJson(io::parseJsonText(text, source), source);
}

}  // namespace

void bindModel(py::module_& m) {
  py::class_<dynamics::Model>(m, "Model", "A contact force model (docs/MODEL.md section 3).")
      .def_static("from_file", &formats::readModelFile, py::arg("path"))
      .def_static("from_json", &fromJsonText, py::arg("text"), py::arg("source") = "dict")
      .def("to_json",
           [](const dynamics::Model& model) { return formats::modelToJson(model).dump(); })
      .def_property_readonly("effects", &dynamics::Model::effectIds)
      .def_property_readonly("parameter_names", &dynamics::Model::parameterNames)
      .def("parameter", &dynamics::Model::parameter, py::arg("name"))
      .def("set_parameter", &dynamics::Model::setParameter, py::arg("name"), py::arg("value"))
      .def("wrench", &wrench, py::arg("contact"), py::arg("v_c") = Eigen::Vector3d::Zero().eval(),
           py::arg("w") = Eigen::Vector3d::Zero().eval(),
           "Wrench on body A at the contact centroid for a patch or aggregate of contact().");
}

}  // namespace vcontact::python
