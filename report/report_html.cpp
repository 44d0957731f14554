#include "report/report_html.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "geometry/error.hpp"
#include "geometry/primitives.hpp"
#include "io/output_file.hpp"
#include "report/svg_chart.hpp"

namespace vcontact::report {
namespace {

using validation::FitResult;

// Points drawn per series: a 6000-sample record is decimated by a stride so that the page
// stays small; 1500 points exceed the pixel width of a chart.
constexpr std::size_t kMaxPointsPerSeries = 1500;
// Chart widths: the page body is 1100 px wide; regime panels go three to a row.
constexpr int kPageWidth = 1060;
constexpr int kPanelWidth = 350;

std::string num(double v, int digits = 4) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

std::size_t strideOf(std::size_t n) {
  return std::max<std::size_t>(1, n / kMaxPointsPerSeries + 1);
}

Series series(const std::string& label, const std::vector<double>& x, const Eigen::VectorXd& y,
              bool markers = false) {
  Series s;
  s.label = label;
  s.markers = markers;
  const std::size_t stride = strideOf(x.size());
  for (std::size_t i = 0; i < x.size(); i += stride) {
    s.x.push_back(x[i]);
    s.y.push_back(y[static_cast<Eigen::Index>(i)]);
  }
  return s;
}

std::string unitOf(const std::string& output) { return output[0] == 'f' ? "N" : "N·m"; }

void measuredVsModel(std::ostringstream& h, const ReportInput& in, const std::vector<double>& t) {
  h << "<h2>Measured and model</h2>\n";
  const FitResult& first = *in.stages.front().fit;
  const FitResult& last = *in.stages.back().fit;
  for (std::size_t k = 0; k < first.comparison.outputs.size(); ++k) {
    const auto& o = first.comparison.outputs[k];
    std::vector<Series> s = {series("measured", t, o.measured, true),
                             series("model: " + in.stages.front().label, t, o.predicted)};
    if (in.stages.size() > 1) {
      s.push_back(
          series("model: " + in.stages.back().label, t, last.comparison.outputs[k].predicted));
    }
    h << lineChart({o.output + ": measured and model", "t [s]",
                    o.output + " [" + unitOf(o.output) + "]", kPageWidth, 300},
                   s)
      << '\n';
  }
}

void residuals(std::ostringstream& h, const ReportInput& in, const std::vector<double>& t) {
  h << "<h2>Residuals of the final model, " << escapeXml(in.stages.back().label)
    << " (shaded: where it fails)</h2>\n";
  for (const auto& o : in.stages.back().fit->comparison.outputs) {
    std::vector<Window> windows;
    for (const auto& w : in.where) {
      if (w.output == o.output) windows.push_back({w.t0, w.t1, "chi " + num(w.chi, 3)});
    }
    h << lineChart({o.output + ": residual (measured − model)", "t [s]",
                    "residual [" + unitOf(o.output) + "]", kPageWidth, 300},
                   {series("residual", t, o.residual)}, windows)
      << '\n';
  }
  if (in.where.empty()) {
    h << "<p>No window where the moving chi exceeds 3.</p>\n";
    return;
  }
  h << "<table><tr><th>output</th><th>phase</th><th>t0 [s]</th><th>t1 [s]</th><th>chi</th>"
    << "<th>regime</th></tr>\n";
  for (const auto& w : in.where) {
    h << "<tr><td>" << w.output << "</td><td>" << escapeXml(w.phase) << "</td><td>" << num(w.t0)
      << "</td><td>" << num(w.t1) << "</td><td>" << num(w.chi, 3) << "</td><td>"
      << escapeXml(w.regime) << "</td></tr>\n";
  }
  h << "</table>\n";
}

void residualsAgainstRegime(std::ostringstream& h, const ReportInput& in) {
  h << "<h2>Normalised residuals of the final model against the regime variables that "
       "vary</h2>\n";
  const FitResult& f = *in.stages.back().fit;
  struct Var {
    const char* label;
    double (*get)(const validation::RegimeSample&);
  };
  const Var vars[] = {
      {"sliding speed |v_t| [m/s]", [](const validation::RegimeSample& r) { return r.speed; }},
      {"spin ratio r_gyr|ω_n|/|v_t|",
       [](const validation::RegimeSample& r) { return r.spin_ratio; }},
      {"time without tangential motion [s]",
       [](const validation::RegimeSample& r) { return r.time_at_rest; }},
      {"rest before this motion [s]",
       [](const validation::RegimeSample& r) { return r.preceding_rest; }},
      {"penetration rate [m/s]",
       [](const validation::RegimeSample& r) { return r.penetration_rate; }},
      {"normal load f_n [N]", [](const validation::RegimeSample& r) { return r.load; }}};
  for (const auto& v : vars) {
    std::vector<double> x;
    for (const auto& r : f.prediction.regime) x.push_back(v.get(r));
    const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
    if (x.empty() || *lo == *hi) continue;  // constant over the record: nothing to show
    std::vector<Series> s;
    for (const auto& o : f.comparison.outputs)
      s.push_back(series(o.output, x, o.residual / o.sigma, true));
    h << lineChart({std::string("residual/σ against ") + v.label, v.label, "residual / σ",
                    kPanelWidth, 260},
                   s)
      << '\n';
  }
}

std::string candidateNote(const validation::Candidate& c) {
  if (c.accepted) return "accepted";
  if (!c.redundantWith.empty()) return "adds nothing beyond " + c.redundantWith;
  return c.rejected;
}

void candidateTable(std::ostringstream& h, const ReportInput& in) {
  if (!in.ranking) return;
  h << "<h2>Candidate effects for the final model (ranked by ΔBIC; accepted when ΔBIC &lt; −"
    << num(validation::kBicMargin) << ", parameters inside their bounds and the held-out χ² of "
    << validation::kCvBlocks << "-block cross-validation lower by more than "
    << num(validation::kHeldOutMargin) << ")</h2>\n<table><tr><th>effect</th><th>adds</th>"
    << "<th>chi</th><th>ΔBIC</th><th>held-out χ²</th><th>fitted parameters</th><th>note</th>"
    << "</tr>\n";
  for (const auto& c : *in.ranking) {
    std::ostringstream added, params;
    for (const auto& a : c.added) added << a << ' ';
    h << "<tr><td>" << c.effect << "</td><td>" << added.str() << "</td>";
    if (!c.error.empty()) {
      h << "<td></td><td></td><td></td><td></td><td>" << escapeXml(c.error) << "</td></tr>\n";
      continue;
    }
    for (const auto& p : c.fit.parameters) {
      if (p.fixed) continue;
      params << p.name << " = " << num(p.value);
      if (!p.atBound.empty()) params << " <b>(at " << escapeXml(p.atBound) << " bound)</b>";
      params << "<br>";
    }
    h << "<td>" << num(c.fit.comparison.chi) << "</td><td>" << num(c.deltaBic, 6) << "</td><td>"
      << (std::isnan(c.heldOutChi2) ? "" : num(c.heldOutChi2, 6)) << "</td><td>" << params.str()
      << "</td><td>" << escapeXml(candidateNote(c)) << "</td></tr>\n";
  }
  h << "</table>\n";
}

// "0.42 (0.35 .. 0.5), FAR" for the direct estimate of `name`; empty when there is none.
std::string directText(const ReportInput& in, const std::string& name) {
  if (!in.direct) return {};
  for (const auto& e : *in.direct) {
    if (e.parameter != name) continue;
    return num(e.value, 3) + " (" + num(e.low, 3) + " .. " + num(e.high, 3) + ")" +
           (e.far ? ", FAR FROM THE FIT" : "");
  }
  return {};
}

// The direct estimates with their methods (those of no model parameter too: lags, the normal
// law's exponent).
void directTable(std::ostringstream& h, const ReportInput& in) {
  if (!in.direct || in.direct->empty()) return;
  h << "<h2>Direct estimates: what the record says without the model</h2>\n<table><tr>"
    << "<th>estimate</th><th>value</th><th>range</th><th>unit</th><th>fitted</th>"
    << "<th>how</th></tr>\n";
  for (const auto& e : *in.direct) {
    h << "<tr><td>" << escapeXml(e.parameter) << "</td><td>" << num(e.value, 4) << "</td><td>"
      << num(e.low, 3) << " .. " << num(e.high, 3) << "</td><td>" << escapeXml(e.unit)
      << "</td><td>" << (std::isnan(e.fitted) ? "" : num(e.fitted, 4))
      << (e.far ? " <b>(far)</b>" : "") << "</td><td>" << escapeXml(e.method) << "</td></tr>\n";
  }
  h << "</table>\n";
}

void parameterTable(std::ostringstream& h, const ReportInput& in) {
  const FitResult& f = *in.stages.back().fit;
  h << "<h2>Parameters of the final model, " << escapeXml(in.stages.back().label)
    << "</h2>\n<table><tr><th>parameter</th><th>value</th><th>std error</th><th>unit</th>"
    << "<th>status</th><th>direct estimate</th></tr>\n";
  for (const auto& p : f.parameters) {
    const std::string err = p.fixed ? "" : (std::isfinite(p.stdError) ? num(p.stdError, 3) : "∞");
    const std::string held = in.command == "compare" ? "as given" : "fixed";
    std::string status = p.fixed ? held : (p.identifiable ? "fitted" : "not identifiable");
    if (!p.fixed && !p.atBound.empty()) status += ", AT " + p.atBound + " BOUND";
    h << "<tr><td>" << p.name << "</td><td>" << num(p.value, 6) << "</td><td>" << err << "</td><td>"
      << escapeXml(p.unit) << "</td><td>" << escapeXml(status) << "</td><td>"
      << escapeXml(directText(in, p.name)) << "</td></tr>\n";
  }
  h << "</table>\n";
  if (f.warnings.empty()) return;
  h << "<ul class=\"warnings\">";
  for (const auto& w : f.warnings) h << "<li>" << escapeXml(w) << "</li>";
  h << "</ul>\n";
}

// chi of each stage as bars (compare, fit), or fitted and held-out chi against the stage
// number with a key (diagnose): held-out chi = sqrt(held-out χ² / residual count).
void chiBars(std::ostringstream& h, const ReportInput& in) {
  std::vector<std::string> labels;
  std::vector<double> chi;
  for (const auto& s : in.stages) {
    labels.push_back(s.label);
    chi.push_back(s.fit->comparison.chi);
  }
  if (!in.stages.front().stage) {
    h << "<h2>chi of each model stage</h2>\n"
      << barChart({"chi = sqrt(mean (residual/σ)²) as effects are added", "model", "chi"}, labels,
                  chi, 1.0, "noise level (chi = 1)")
      << '\n';
    return;
  }
  // log10: chi falls over decades (100 → 1); 0 is the noise level
  Series fitted{"fitted", {}, {}, "", false},
      held{"held out (5-block cross-validation)", {}, {}, "", false};
  h << "<h2>chi of each stage, fitted and held out</h2>\n<table><tr><th>stage</th><th>model"
    << "</th><th>chi fitted</th><th>chi held out</th><th>verdict</th></tr>\n";
  for (std::size_t i = 0; i < in.stages.size(); ++i) {
    const auto& st = *in.stages[i].stage;
    const double out =
        std::sqrt(st.heldOutChi2 / static_cast<double>(st.baseline.comparison.count));
    fitted.x.push_back(static_cast<double>(i + 1));
    fitted.y.push_back(std::log10(chi[i]));
    held.x.push_back(static_cast<double>(i + 1));
    held.y.push_back(std::log10(out));
    h << "<tr><td>" << i + 1 << "</td><td>" << escapeXml(labels[i]) << "</td><td>" << num(chi[i])
      << "</td><td>" << num(out) << "</td><td>" << escapeXml(st.verdict) << "</td></tr>\n";
  }
  h << "</table>\n"
    << lineChart({"log10 chi per stage, fitted and predicted on held-out blocks (0 = noise level)",
                  "stage (table above)", "log10 chi", kPageWidth, 260, true},
                 {fitted, held})
    << '\n';
}

// The verdict of the final stage in words: effect, rig finding, none, or what is unexplained.
void verdictSection(std::ostringstream& h, const ReportInput& in) {
  if (!in.stages.back().stage) return;
  const auto& st = *in.stages.back().stage;
  h << "<h2>Verdict: " << escapeXml(st.verdict)
    << "</h2>\n<p>Final model: " << escapeXml(in.stages.back().label) << " (effects:";
  for (const auto& e : st.effects) h << ' ' << e;
  h << ").</p>\n";
  h << "<p>Rig candidates (properties of the rig, not of the contact) with ΔBIC &lt; −"
    << num(validation::kBicMargin) << ":";
  bool any = false;
  for (const auto& r : st.rig) {
    if (!(r.deltaBic < -validation::kBicMargin)) continue;
    h << (any ? "; " : " ") << escapeXml(r.text) << " (ΔBIC " << num(r.deltaBic, 5) << ")";
    any = true;
  }
  h << (any ? "" : " none") << ".</p>\n";
  if (st.kind != "unexplained") return;
  const auto& r = st.residual;
  h << "<p>Structure remains that no library effect removes out of sample. The best candidate "
    << "removes " << num(100.0 * st.explainedFraction, 3) << " % of the residual χ²; the noise "
    << "accounts for " << num(100.0 * r.noiseShare, 3) << " %. Worst output " << r.output;
  if (r.frequency > 0.0) {
    h << "; its residual rings at " << num(r.frequency, 3) << " Hz ("
      << num(100.0 * r.frequencyShare, 3) << " % of its variance)";
  }
  h << ".</p>\n<ul>";
  for (const auto& [name, c] : r.correlation)
    h << "<li>|residual| against " << escapeXml(name) << ": r = " << num(c, 3) << "</li>";
  h << "</ul>\n";
}

const char* kStyle =
    "body{font-family:sans-serif;max-width:1100px;margin:1em auto;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #ccc;padding:2px 6px;"
    "font-size:13px;vertical-align:top}svg.chart{margin:4px}.warnings{color:#a40}";

// Counts the charts with a non-empty bounding box once the page has rendered.
const char* kCheckScript =
    "<script>window.addEventListener('load',function(){"
    "var c=document.querySelectorAll('svg.chart'),k=0;"
    "for(var i=0;i<c.length;i++){var b=c[i].getBBox();if(b.width>0&&b.height>0)k++;}"
    "document.body.setAttribute('data-charts-rendered',k+'/'+c.length);"
    "document.title=document.title+' ['+k+'/'+c.length+' charts]';});</script>";

}  // namespace

std::string reportHtml(const ReportInput& in) {
  const auto& d = *in.dataset;
  std::vector<double> t;
  for (const auto& s : d.samples) t.push_back(s.t);
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>vcontact " << in.command << ": "
    << escapeXml(d.name) << "</title><style>" << kStyle << "</style></head><body>\n"
    << "<h1>vcontact " << in.command << ": " << escapeXml(d.name) << "</h1>\n<p>"
    << escapeXml(d.notes) << "</p>\n<p>payload: " << escapeXml(geometry::describe(d.payload))
    << "; plate: " << escapeXml(geometry::describe(d.plate)) << "</p>\n<p>" << d.size()
    << " samples; σ per output: ";
  for (const auto& [o, n] : in.noise) {
    h << o << " = " << num(n.sigma, 3) << ' ' << unitOf(o)
      << (n.estimated ? " (estimated from the data)" : " (sidecar)") << "; ";
  }
  h << "</p>\n<p>chi: ";
  for (const auto& s : in.stages)
    h << escapeXml(s.label) << " = " << num(s.fit->comparison.chi) << "; ";
  h << "</p>\n";
  verdictSection(h, in);
  chiBars(h, in);
  measuredVsModel(h, in, t);
  residuals(h, in, t);
  residualsAgainstRegime(h, in);
  candidateTable(h, in);
  parameterTable(h, in);
  directTable(h, in);
  h << kCheckScript << "\n</body></html>\n";
  return h.str();
}

void writeReportHtml(const ReportInput& input, const std::string& path) {
  io::OutputFile file(path);  // opened first: nothing is built for a file that cannot be written
  file.stream() << reportHtml(input);
  file.commit();
}

}  // namespace vcontact::report
