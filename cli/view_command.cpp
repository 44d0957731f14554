// vcontact view OUT_DIR --out view.html: a self-contained 3D playback page of a simulation
// (or of a dynamic dataset's compare: the record as a ghost beside the simulated payload).

#include <iostream>

#include "cli/commands.hpp"
#include "report/view_html.hpp"

namespace vcontact::cli {
namespace {

struct ViewCommandOptions {
  report::ViewOptions view;
  std::string out = "view.html";
};

void runView(const ViewCommandOptions& o) {
  std::vector<std::string> warnings;
  report::writeViewHtml(o.view, o.out, warnings);
  printWarnings(warnings);
  std::cerr << "vcontact: wrote " << o.out << '\n';
}

}  // namespace

void addViewCommand(CLI::App& app) {
  auto opts = std::make_shared<ViewCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "view",
      "Write one self-contained HTML page (three.js inlined) that plays back what "
      "`vcontact simulate --out OUT_DIR` wrote: bodies, contact patches, forces; or what "
      "`vcontact compare` wrote for a dynamic dataset: the payload simulated and recorded "
      "(docs/VIEWER.md).");
  cmd->add_option("OUT_DIR", opts->view.out_dir,
                  "a folder of `vcontact simulate`, or of `compare` on a dynamic dataset")
      ->required();
  cmd->add_option("--out", opts->out, "the HTML file to write")->capture_default_str();
  cmd->add_option("--scenario", opts->view.scenario,
                  "the scenario file (default: the one summary.json names)");
  cmd->add_option("--dataset", opts->view.dataset,
                  "for a folder of `vcontact compare` on a dynamic dataset: the dataset (default: "
                  "the one compare.json names)");
  cmd->add_option("--three-js", opts->view.three_js, "three.js to inline")->capture_default_str();
  cmd->callback([opts] { runView(*opts); });
}

}  // namespace vcontact::cli
