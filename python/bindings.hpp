#pragma once
// The binding files of the extension module (module.cpp defines it).

#include <string>
#include <vector>

#include "dynamics/scenario.hpp"
#include "python/convert.hpp"

namespace vcontact::python {

/// Model: from a file or a dict, parameters, wrench for a contact and relative motion.
void bindModel(py::module_& m);
/// Scenario: load, run, body and pair series as arrays.
void bindScenario(py::module_& m);
/// Dataset: load, columns; compare, fit and diagnose returning their JSON files' content.
void bindDataset(py::module_& m);
/// run_batch: many scenarios on a TBB pool with the GIL released, reduced to per-run figures.
void bindBatch(py::module_& m);

/// The scenario's loads, then its springs: the order of Snapshot::loads.
std::vector<std::string> loadNames(const dynamics::Scenario& scenario);

}  // namespace vcontact::python
