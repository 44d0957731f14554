// vcontact.Dataset and compare / fit / diagnose: the validation workflow of docs/DATASET.md,
// returning what `vcontact compare | fit | diagnose` write as JSON.

#include "formats/dataset_file.hpp"
#include "formats/model_file.hpp"
#include "geometry/error.hpp"
#include "python/bindings.hpp"
#include "report/validation_output.hpp"
#include "validation/diagnose.hpp"

namespace vcontact::python {
namespace {

struct LoadedDataset {
  formats::DatasetReadResult read;
};

// Every parameter held: the model exactly as given (as `vcontact compare` does).
validation::FitResult asGiven(validation::Replayer& replayer, const validation::NoiseLevels& noise,
                              dynamics::Model model) {
  model.setFixed(model.parameterNames());
  return validation::fit(replayer, noise, model);
}

// compare.json's content.
std::string compareJson(const LoadedDataset& d, const dynamics::Model& model) {
  const validation::Dataset& data = d.read.dataset;
  const auto noise = validation::noiseLevels(data);
  py::gil_scoped_release release;
  validation::Replayer replayer(data);
  const validation::FitResult r = asGiven(replayer, noise, model);
  return report::comparisonJson(r.comparison, noise).dump();
}

// fit.json's content (its "model" is the fitted model file, model.json).
std::string fitJson(const LoadedDataset& d, const dynamics::Model& model, const std::string& loss,
                    int maxIterations) {
  const validation::Dataset& data = d.read.dataset;
  const validation::Loss l = validation::parseLoss(loss);
  if (maxIterations < 1) throw InputError("max_iterations", "expected a positive count");
  const auto noise = validation::noiseLevels(data);
  py::gil_scoped_release release;
  validation::Replayer replayer(data);
  validation::FitResult r = validation::fit(replayer, noise, model, {l, maxIterations});
  const auto direct = validation::estimatesBeside(data, noise, r);  // as `vcontact fit` shows
  return report::fitJson(r, noise, l, &direct).dump();
}

// diagnosis.json's content, plus "model": the final model file (model.json).
std::string diagnoseJson(const LoadedDataset& d, const dynamics::Model& model, bool iterate,
                         const std::string& loss, int maxIterations) {
  const validation::Dataset& data = d.read.dataset;
  const validation::Loss l = validation::parseLoss(loss);
  if (maxIterations < 1) throw InputError("max_iterations", "expected a positive count");
  const auto noise = validation::noiseLevels(data);
  py::gil_scoped_release release;
  const validation::Diagnosis diag =
      validation::diagnose(data, noise, model, {{l, maxIterations}, iterate});
  nlohmann::json j = report::diagnosisJson(diag, noise);
  j["model"] = formats::modelToJson(diag.final().model);
  return j.dump();
}

py::dict columns(const LoadedDataset& d) {
  py::dict out;
  for (const auto& [name, column] : d.read.dataset.columns) {
    out[py::str(name)] = Eigen::VectorXd(column);
  }
  return out;
}

}  // namespace

void bindDataset(py::module_& m) {
  py::class_<LoadedDataset>(m, "Dataset", "A rig measurement (docs/DATASET.md).")
      .def_static(
          "load", [](const std::string& path) { return LoadedDataset{formats::readDataset(path)}; },
          py::arg("path"))
      .def_property_readonly("name", [](const LoadedDataset& d) { return d.read.dataset.name; })
      .def_property_readonly("outputs",
                             [](const LoadedDataset& d) { return d.read.dataset.outputs; })
      .def_property_readonly("noise", [](const LoadedDataset& d) { return d.read.dataset.noise; })
      .def_property_readonly("warnings", [](const LoadedDataset& d) { return d.read.warnings; })
      .def_property_readonly("size", [](const LoadedDataset& d) { return d.read.dataset.size(); })
      .def_property_readonly("columns", &columns);
  m.def("compare_json", &compareJson, py::arg("dataset"), py::arg("model"));
  m.def("fit_json", &fitJson, py::arg("dataset"), py::arg("model"), py::arg("loss") = "none",
        py::arg("max_iterations") = 100);
  m.def("diagnose_json", &diagnoseJson, py::arg("dataset"), py::arg("model"),
        py::arg("iterate") = false, py::arg("loss") = "none", py::arg("max_iterations") = 100);
}

}  // namespace vcontact::python
