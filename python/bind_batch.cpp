// vcontact._vcontact.run_batch: many scenarios run in C++ on a TBB thread pool with the GIL
// released, each reduced as it runs to the figures a study collects (docs/STUDY.md, "Run
// quantities"): final pose and velocity, extremes of the position, peak contact and load
// forces, time in contact, the impacts, the first time a coordinate crosses a level, the
// status and wall time. A run that fails (bad scenario, stopped integration) is a result with
// its status and message, never an exception: one bad run does not lose the others.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>
#include <time.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"
#include "geometry/error.hpp"
#include "python/bindings.hpp"

namespace vcontact::python {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// One run: a scenario's JSON text, the name its messages use, and the folder its relative
/// paths (meshes, models, tables) are resolved against.
struct BatchItem {
  std::string json;
  std::string source;
  std::string base_dir;
};

/// The first output time at which body `body`'s origin coordinate `axis` (0 x, 1 y, 2 z) is
/// below (or above) `level`, placed linearly between the two samples around the crossing.
struct CrossingEvent {
  std::string name;
  std::string body;
  int axis = 2;
  double level = 0.0;  ///< m
  bool below = true;
};

struct BodyFigures {
  Eigen::Vector3d final_p = Eigen::Vector3d::Constant(kNaN);
  Eigen::Vector4d final_q = Eigen::Vector4d::Constant(kNaN);  ///< w, x, y, z
  Eigen::Vector3d final_v = Eigen::Vector3d::Constant(kNaN);
  Eigen::Vector3d final_w = Eigen::Vector3d::Constant(kNaN);
  Eigen::Vector3d min_p = Eigen::Vector3d::Constant(kNaN);
  Eigen::Vector3d max_p = Eigen::Vector3d::Constant(kNaN);
};

struct PairFigures {
  double peak_f_n = 0.0;        ///< N, largest f_n at an output time
  double peak_force = 0.0;      ///< N, largest |f| of the pair's wrench on A at an output time
  double final_f_n = kNaN;      ///< N
  double contact_time = 0.0;    ///< s, output intervals that end in contact
  double first_contact = kNaN;  ///< s, first output time in contact
  int max_patches = 0;
  std::vector<dynamics::ImpactRecord> impacts;
};

struct LoadFigures {
  double peak_force = 0.0;  ///< N, largest |f| at an output time
  Eigen::Vector3d final_force = Eigen::Vector3d::Constant(kNaN);
  Eigen::Vector3d final_torque = Eigen::Vector3d::Constant(kNaN);
};

struct BatchOutcome {
  std::string status = "error";  ///< "completed", "stopped" (integration) or "error" (input)
  std::string message;
  std::string stop_cause;
  double stop_time = kNaN;
  double wall_time = 0.0;  ///< s, reading the scenario included
  double cpu_time = 0.0;   ///< s of the thread that ran it (CLOCK_THREAD_CPUTIME_ID), likewise
  dynamics::SimulationSummary summary;
  std::vector<std::string> body_names, pair_names, load_names;
  std::vector<BodyFigures> bodies;
  std::vector<PairFigures> pairs;
  std::vector<LoadFigures> loads;
  std::vector<double> events;  ///< s per CrossingEvent, NaN when never crossed
};

// Folds one output snapshot into the figures.
class Reducer {
 public:
  Reducer(BatchOutcome& out, const std::vector<CrossingEvent>& events) : out_(out) {
    for (const CrossingEvent& e : events) {
      int index = -1;
      for (std::size_t i = 0; i < out.body_names.size(); ++i)
        if (out.body_names[i] == e.body) index = static_cast<int>(i);
      if (index < 0) throw InputError("event '" + e.name + "'", "no body named '" + e.body + "'");
      body_of_event_.push_back(index);
    }
    out.events.assign(events.size(), kNaN);
    events_ = &events;
  }

  void observe(const dynamics::Snapshot& s) {
    for (std::size_t i = 0; i < s.bodies.size(); ++i) observeBody(s.bodies[i], out_.bodies[i]);
    for (std::size_t k = 0; k < s.pairs.size(); ++k) observePair(s.t, s.pairs[k], out_.pairs[k]);
    for (std::size_t k = 0; k < s.loads.size(); ++k) {
      LoadFigures& f = out_.loads[k];
      f.peak_force = std::max(f.peak_force, s.loads[k].wrench.f_W.norm());
      f.final_force = s.loads[k].wrench.f_W;
      f.final_torque = s.loads[k].wrench.tau_W;
    }
    observeEvents(s);
    last_t_ = s.t;
    first_ = false;
  }

 private:
  static void observeBody(const dynamics::BodyKinematics& k, BodyFigures& f) {
    const Eigen::Vector3d p = k.X_WB.translation();
    const Eigen::Quaterniond q(k.X_WB.linear());
    f.final_p = p;
    f.final_q = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
    f.final_v = k.pointVelocity(p);
    f.final_w = k.w_WB;
    f.min_p = f.min_p.hasNaN() ? p : Eigen::Vector3d(f.min_p.cwiseMin(p));
    f.max_p = f.max_p.hasNaN() ? p : Eigen::Vector3d(f.max_p.cwiseMax(p));
  }

  void observePair(double t, const dynamics::PairOutput& p, PairFigures& f) const {
    f.peak_f_n = std::max(f.peak_f_n, p.result.f_n);
    f.peak_force = std::max(f.peak_force, p.result.wrench.f_W.norm());
    f.final_f_n = p.result.f_n;
    f.max_patches = std::max(f.max_patches, p.patch_count);
    if (!p.cv.inContact()) return;
    if (std::isnan(f.first_contact)) f.first_contact = t;
    if (!first_) f.contact_time += t - last_t_;
  }

  void observeEvents(const dynamics::Snapshot& s) {
    for (std::size_t e = 0; e < events_->size(); ++e) {
      const CrossingEvent& ev = (*events_)[e];
      const double x = s.bodies[body_of_event_[e]].X_WB.translation()[ev.axis];
      const bool crossed = ev.below ? x < ev.level : x > ev.level;
      if (std::isnan(out_.events[e]) && crossed) {
        const double x0 = last_x_.empty() ? x : last_x_[e];
        // Linear between the previous sample (x0 at last_t_) and this one (x at s.t).
        const double w = (first_ || x == x0) ? 1.0 : (ev.level - x0) / (x - x0);
        out_.events[e] = first_ ? s.t : last_t_ + w * (s.t - last_t_);
      }
      last_x_.resize(events_->size());
      last_x_[e] = x;
    }
  }

  BatchOutcome& out_;
  const std::vector<CrossingEvent>* events_ = nullptr;
  std::vector<int> body_of_event_;
  std::vector<double> last_x_;
  double last_t_ = 0.0;
  bool first_ = true;
};

void nameParts(const dynamics::Scenario& sc, BatchOutcome& out) {
  for (const auto& b : sc.bodies) out.body_names.push_back(b.name);
  for (const auto& p : sc.pairs) out.pair_names.push_back(p.name);
  out.load_names = loadNames(sc);
  out.bodies.resize(out.body_names.size());
  out.pairs.resize(out.pair_names.size());
  out.loads.resize(out.load_names.size());
}

void simulate(const BatchItem& item, const std::vector<CrossingEvent>& events, BatchOutcome& out) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(item.json);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(item.source, std::string("not JSON: ") + e.what());
  }
  formats::ScenarioFile file = formats::scenarioFromJson(j, item.source, item.base_dir);
  dynamics::Simulator sim(std::move(file.scenario));
  sim.setOutputDepths(false);  // no figure reads the output depth; it costs a query per sample
  nameParts(sim.scenario(), out);
  Reducer reducer(out, events);
  try {
    sim.run([&](const dynamics::Snapshot& s) { reducer.observe(s); }, [](double) {}, out.summary);
    out.status = "completed";
  } catch (const dynamics::SimulationError& e) {
    out.status = "stopped";
    out.message = e.what();
    out.stop_cause = dynamics::stopCauseName(e.cause());
    out.stop_time = e.time();
  }
  for (const dynamics::ImpactRecord& r : out.summary.impacts) {
    for (std::size_t k = 0; k < out.pair_names.size(); ++k)
      if (out.pair_names[k] == r.pair) out.pairs[k].impacts.push_back(r);
  }
}

// One run, its failures caught: an input error or an internal one is the run's status.
double threadCpuSeconds() {
  timespec t{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

BatchOutcome runOne(const BatchItem& item, const std::vector<CrossingEvent>& events) {
  BatchOutcome out;
  const auto start = std::chrono::steady_clock::now();
  const double cpu0 = threadCpuSeconds();
  try {
    simulate(item, events, out);
  } catch (const InputError& e) {
    out = BatchOutcome{};
    out.message = e.what();
  } catch (const std::exception& e) {
    out = BatchOutcome{};
    out.message = std::string("internal error: ") + e.what();
  }
  out.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.cpu_time = threadCpuSeconds() - cpu0;
  return out;
}

py::dict bodyDict(const BodyFigures& f) {
  py::dict d;
  d["final_p"] = f.final_p;
  d["final_q"] = f.final_q;
  d["final_v"] = f.final_v;
  d["final_w"] = f.final_w;
  d["min_p"] = f.min_p;
  d["max_p"] = f.max_p;
  return d;
}

// The impacts as columns named by summary.json's keys, one row per impact.
constexpr std::pair<const char*, double dynamics::ImpactRecord::*> kImpactColumns[] = {
    {"start_s", &dynamics::ImpactRecord::start},
    {"duration_s", &dynamics::ImpactRecord::duration},
    {"normal_impulse_Ns", &dynamics::ImpactRecord::impulse},
    {"approach_speed_m_s", &dynamics::ImpactRecord::approach_speed},
    {"separation_speed_m_s", &dynamics::ImpactRecord::separation_speed},
    {"restitution", &dynamics::ImpactRecord::restitution},
    {"predicted_rebound_m_s", &dynamics::ImpactRecord::predicted_rebound}};

py::dict impactColumns(const std::vector<dynamics::ImpactRecord>& impacts) {
  py::dict d;
  for (const auto& [name, member] : kImpactColumns) {
    py::array_t<double> column(static_cast<py::ssize_t>(impacts.size()));
    for (std::size_t i = 0; i < impacts.size(); ++i)
      column.mutable_at(static_cast<py::ssize_t>(i)) = impacts[i].*member;
    d[name] = column;
  }
  return d;
}

py::dict pairDict(const PairFigures& f) {
  py::dict d;
  d["peak_f_n"] = f.peak_f_n;
  d["peak_force"] = f.peak_force;
  d["final_f_n"] = f.final_f_n;
  d["contact_time"] = f.contact_time;
  d["first_contact"] = f.first_contact;
  d["max_patches"] = f.max_patches;
  d["impacts"] = impactColumns(f.impacts);
  return d;
}

py::dict loadDict(const LoadFigures& f) {
  py::dict d;
  d["peak_force"] = f.peak_force;
  d["final_force"] = f.final_force;
  d["final_torque"] = f.final_torque;
  return d;
}

py::dict outcomeDict(const BatchOutcome& o, const std::vector<CrossingEvent>& events) {
  py::dict d, bodies, pairs, loads, ev, sim;
  d["status"] = o.status;
  d["message"] = o.message;
  d["stop_cause"] = o.stop_cause;
  d["stop_time"] = o.stop_time;
  d["wall_time"] = o.wall_time;
  d["cpu_time"] = o.cpu_time;
  sim["simulated_time"] = o.summary.simulated_time;
  sim["wall_time"] = o.summary.wall_time;
  sim["steps"] = o.summary.steps;
  sim["rejected_steps"] = o.summary.rejected_steps;
  sim["contact_evaluations"] = o.summary.contact_evaluations;
  d["sim"] = sim;
  for (std::size_t i = 0; i < o.bodies.size(); ++i)
    bodies[py::str(o.body_names[i])] = bodyDict(o.bodies[i]);
  for (std::size_t k = 0; k < o.pairs.size(); ++k)
    pairs[py::str(o.pair_names[k])] = pairDict(o.pairs[k]);
  for (std::size_t k = 0; k < o.loads.size(); ++k)
    loads[py::str(o.load_names[k])] = loadDict(o.loads[k]);
  for (std::size_t e = 0; e < o.events.size(); ++e) ev[py::str(events[e].name)] = o.events[e];
  d["bodies"] = bodies;
  d["pairs"] = pairs;
  d["loads"] = loads;
  d["events"] = ev;
  return d;
}

CrossingEvent crossingFrom(const py::handle& h) {
  const auto d = py::reinterpret_borrow<py::dict>(h);
  CrossingEvent e;
  e.name = d["name"].cast<std::string>();
  e.body = d["body"].cast<std::string>();
  e.axis = d["axis"].cast<int>();
  e.level = d["level"].cast<double>();
  e.below = d["below"].cast<bool>();
  if (e.axis < 0 || e.axis > 2)
    throw InputError("event '" + e.name + "'", "axis: expected 0, 1 or 2");
  return e;
}

/// items: list of (json, source, base_dir); events: list of {name, body, axis, level, below};
/// threads: the pool's size (0: TBB's default, every core).
py::list runBatch(const std::vector<std::tuple<std::string, std::string, std::string>>& items,
                  const py::list& eventList, int threads) {
  std::vector<BatchItem> runs;
  for (const auto& [json, source, dir] : items) runs.push_back({json, source, dir});
  std::vector<CrossingEvent> events;
  for (const py::handle h : eventList) events.push_back(crossingFrom(h));
  if (threads < 0) throw InputError("threads", "expected 0 (every core) or a positive count");
  std::vector<BatchOutcome> outcomes(runs.size());
  {
    py::gil_scoped_release release;
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
      // One run per task: runs differ in cost by orders of magnitude (a jam against a clean
      // insertion), so the pool balances them one by one.
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, runs.size(), 1),
          [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i)
              outcomes[i] = runOne(runs[i], events);
          },
          tbb::simple_partitioner());
    });
  }
  py::list results;
  for (const BatchOutcome& o : outcomes) results.append(outcomeDict(o, events));
  return results;
}

}  // namespace

void bindBatch(py::module_& m) {
  m.def("run_batch", &runBatch, py::arg("items"), py::arg("events"), py::arg("threads") = 0,
        "Runs scenarios (JSON text, source name, base folder) on a TBB pool, GIL released; "
        "returns one dict of figures per run (docs/PYTHON.md, \"Batches\").");
}

}  // namespace vcontact::python
