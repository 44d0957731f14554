// vcontact.Scenario: a scenario file (docs/SCENARIO.md) loaded, run, and its body and pair
// series handed over as NumPy arrays.

#include <chrono>
#include <optional>
#include <sstream>

#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"
#include "geometry/error.hpp"
#include "python/bindings.hpp"
#include "report/simulation_csv.hpp"
#include "report/simulation_summary.hpp"
#include "report/view_html.hpp"

namespace vcontact::python {
namespace {

struct LoadedScenario {
  formats::ScenarioFile file;
  std::string path;
};

// A growing table of doubles that becomes a NumPy array without a copy (the array owns it).
struct Series {
  std::vector<double> values;
  int width = 1;
  void add(const Eigen::Ref<const Eigen::VectorXd>& v) {
    values.insert(values.end(), v.data(), v.data() + v.size());
  }
  py::array release() {
    auto* owned = new std::vector<double>(std::move(values));
    py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
    const auto rows = static_cast<py::ssize_t>(owned->size() / static_cast<std::size_t>(width));
    std::vector<py::ssize_t> shape{rows};
    if (width > 1) shape.push_back(width);
    return py::array_t<double>(shape, owned->data(), owner);
  }
};

using Columns = std::vector<std::pair<std::string, Series>>;

py::dict released(Columns& columns) {
  py::dict d;
  for (auto& [name, s] : columns) d[py::str(name)] = s.release();
  return d;
}

Columns bodyColumns() {
  return {{"t", {{}, 1}}, {"p", {{}, 3}}, {"q", {{}, 4}}, {"v", {{}, 3}}, {"w", {{}, 3}}};
}

Columns pairColumns() {
  return {{"t", {{}, 1}},      {"V", {{}, 1}},        {"depth", {{}, 1}},  {"area", {{}, 1}},
          {"r_gyr", {{}, 1}},  {"centroid", {{}, 3}}, {"normal", {{}, 3}}, {"force", {{}, 3}},
          {"torque", {{}, 3}}, {"f_n", {{}, 1}},      {"s", {{}, 1}},      {"mu_max", {{}, 1}}};
}

// A load's or spring's wrench on its body, as loads.csv writes it: the point where it acts,
// the force and the torque about that point, in W.
Columns loadColumns() {
  return {{"t", {{}, 1}}, {"p", {{}, 3}}, {"force", {{}, 3}}, {"torque", {{}, 3}}};
}

void record(const dynamics::Snapshot& s, std::vector<Columns>& bodies, std::vector<Columns>& pairs,
            std::vector<Columns>& loads) {
  const Eigen::Matrix<double, 1, 1> t(s.t);
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const auto& k = s.bodies[i];
    const Eigen::Quaterniond q(k.X_WB.linear());
    const Eigen::Vector4d wxyz(q.w(), q.x(), q.y(), q.z());
    const Eigen::Vector3d p = k.X_WB.translation();
    const Eigen::Vector3d v = k.pointVelocity(p);
    auto& c = bodies[i];
    c[0].second.add(t);
    c[1].second.add(p);
    c[2].second.add(wxyz);
    c[3].second.add(v);
    c[4].second.add(k.w_WB);
  }
  for (std::size_t k = 0; k < s.pairs.size(); ++k) {
    const auto& p = s.pairs[k];
    auto& c = pairs[k];
    const double scalars[] = {s.t, p.cv.volume, p.cv.depth, p.cv.area, p.cv.r_gyr};
    for (int j = 0; j < 5; ++j) c[j].second.values.push_back(scalars[j]);
    c[5].second.add(p.cv.p_WC);
    c[6].second.add(p.cv.n_W);
    c[7].second.add(p.result.wrench.f_W);
    c[8].second.add(p.result.wrench.tau_W);
    c[9].second.values.push_back(p.result.f_n);
    c[10].second.values.push_back(p.result.s);
    c[11].second.values.push_back(p.result.mu_max);
  }
  for (std::size_t k = 0; k < s.loads.size(); ++k) {
    auto& c = loads[k];
    c[0].second.values.push_back(s.t);
    c[1].second.add(s.loads[k].p_W);
    c[2].second.add(s.loads[k].wrench.f_W);
    c[3].second.add(s.loads[k].wrench.tau_W);
  }
}

// The CLI's limit on the rows a run writes (report::kMaxOutputRows), before the run: here the
// rows are also held in memory, as NumPy arrays.
void checkRowCount(const LoadedScenario& s) {
  const std::uint64_t rows = report::outputRowCount(s.file.scenario, s.file.outputs);
  if (rows <= report::kMaxOutputRows) return;
  const dynamics::SimulationSettings& set = s.file.scenario.settings;
  std::ostringstream m;
  m << "the run would write " << rows << " rows (" << set.duration << " s at " << set.output_rate_hz
    << " Hz), more than the limit of " << report::kMaxOutputRows
    << "; lower the scenario's output rate";
  throw InputError(s.path, m.str());
}

// Ctrl-C during a run: Python runs its signal handlers only when asked, and the run does not
// hold the GIL. The step loop's progress hook asks (PyErr_CheckSignals) at most every
// kSignalPoll of wall time; a handler that raises (KeyboardInterrupt) ends the run.
struct Interrupted {};

class SignalPoll {
 public:
  void operator()() {
    constexpr auto kSignalPoll = std::chrono::milliseconds(50);
    const auto now = std::chrono::steady_clock::now();
    if (now < next_) return;
    next_ = now + kSignalPoll;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw Interrupted{};
  }

 private:
  std::chrono::steady_clock::time_point next_ = std::chrono::steady_clock::now();
};

// Runs the scenario; with `out`, also writes what `vcontact simulate --out` writes there.
py::dict run(const LoadedScenario& s, const std::optional<std::string>& out) {
  checkRowCount(s);
  dynamics::Simulator sim(s.file.scenario);
  std::vector<Columns> bodies(sim.scenario().bodies.size(), bodyColumns());
  std::vector<Columns> pairs(sim.scenario().pairs.size(), pairColumns());
  const std::vector<std::string> names = loadNames(sim.scenario());
  std::vector<Columns> loads(names.size(), loadColumns());
  std::unique_ptr<report::SimulationCsvWriter> writer;
  if (out)
    writer = std::make_unique<report::SimulationCsvWriter>(*out, sim.scenario(), s.file.outputs);
  dynamics::SimulationSummary summary;
  std::optional<report::StopInfo> stop;
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    SignalPoll poll;
    try {
      sim.run(
          [&](const dynamics::Snapshot& snap) {
            record(snap, bodies, pairs, loads);
            if (writer) writer->write(snap);
          },
          [&](double) { poll(); }, summary);
    } catch (const dynamics::SimulationError& e) {
      stop = report::StopInfo{e};
    } catch (const Interrupted&) {
      interrupted = true;
    }
  }
  if (interrupted) throw py::error_already_set();  // the handler's exception, KeyboardInterrupt
  // A stopped run keeps its output and reports the stop in its summary, as `vcontact simulate`.
  const nlohmann::json j =
      writer ? report::finishSimulationOutput(*writer, *out, summary, s.path, stop)
             : report::simulationSummaryJson(summary, s.path, stop);
  py::dict result, b, p, l;
  for (std::size_t i = 0; i < bodies.size(); ++i)
    b[py::str(sim.scenario().bodies[i].name)] = released(bodies[i]);
  for (std::size_t k = 0; k < pairs.size(); ++k)
    p[py::str(sim.scenario().pairs[k].name)] = released(pairs[k]);
  for (std::size_t k = 0; k < loads.size(); ++k) l[py::str(names[k])] = released(loads[k]);
  result["bodies"] = b;
  result["pairs"] = p;
  result["loads"] = l;
  result["summary"] = toPython(j);
  return result;
}

LoadedScenario load(const std::string& path) { return {formats::readScenarioFile(path), path}; }

// A scenario from its JSON text; `source` names it in messages, relative paths are resolved
// against `base_dir` (a study's run: the base scenario's folder).
LoadedScenario fromJson(const std::string& text, const std::string& source,
                        const std::string& base_dir) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(source, std::string("not JSON: ") + e.what());
  }
  return {formats::scenarioFromJson(j, source, base_dir), source};
}

std::vector<std::string> view(const std::string& outDir, const std::string& html,
                              const std::string& scenario, const std::string& dataset) {
  std::vector<std::string> warnings;
  report::ViewOptions o;
  o.out_dir = outDir;
  o.scenario = scenario;
  o.dataset = dataset;
  report::writeViewHtml(o, html, warnings);
  return warnings;
}

}  // namespace

std::vector<std::string> loadNames(const dynamics::Scenario& scenario) {
  std::vector<std::string> names;
  for (const auto& l : scenario.loads) names.push_back(l.name);
  for (const auto& s : scenario.springs) names.push_back(s.name);
  return names;
}

void bindScenario(py::module_& m) {
  py::class_<LoadedScenario>(m, "Scenario", "A scenario file (docs/SCENARIO.md), loaded.")
      .def_static("load", &load, py::arg("path"))
      .def_static("from_json", &fromJson, py::arg("text"), py::arg("source"), py::arg("base_dir"))
      .def_readonly("path", &LoadedScenario::path)
      .def_property_readonly("warnings", [](const LoadedScenario& s) { return s.file.warnings; })
      .def_property_readonly("bodies",
                             [](const LoadedScenario& s) {
                               std::vector<std::string> names;
                               for (const auto& b : s.file.scenario.bodies) names.push_back(b.name);
                               return names;
                             })
      .def_property_readonly("pairs",
                             [](const LoadedScenario& s) {
                               std::vector<std::string> names;
                               for (const auto& p : s.file.scenario.pairs) names.push_back(p.name);
                               return names;
                             })
      .def_property_readonly(
          "duration", [](const LoadedScenario& s) { return s.file.scenario.settings.duration; })
      .def("run", &run, py::arg("out") = py::none());
  m.def("view", &view, py::arg("out_dir"), py::arg("html"), py::arg("scenario") = "",
        py::arg("dataset") = "");
}

}  // namespace vcontact::python
