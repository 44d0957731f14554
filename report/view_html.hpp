#pragma once
// `vcontact view OUT_DIR`: one self-contained HTML page that plays a simulation back in 3D
// (three.js inlined), from the folder `vcontact simulate` wrote and the scenario it ran, or
// from the folder `vcontact compare` wrote for a dynamic dataset (docs/VIEWER.md).

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace vcontact::report {

/// Where Debian's libjs-three puts the minified three.js.
inline constexpr const char* kDebianThreeJs = "/usr/share/javascript/three/three.min.js";

struct ViewOptions {
  std::string
      out_dir;  ///< what `vcontact simulate --out` (or `compare` of a dynamic dataset) wrote
  std::string scenario;  ///< the scenario file; empty: the "scenario" key of summary.json
  std::string dataset;   ///< a dynamic compare's dataset; empty: the "dataset" key of compare.json
  std::string three_js = kDebianThreeJs;
};

/// What the page plays back, as the JSON object embedded in it: the bodies' meshes in their own
/// frames, their poses at every output time, and per pair the wrench series and the contact
/// patches at every time (from pair_<name>_patches.csv when present, else the aggregate
/// columns of pair_<name>.csv). Notes on what was left out go to `warnings`.
/// A folder of `vcontact compare` on a dynamic dataset (compare.json and trajectory.csv, no
/// summary.json) gives the plate, the payload as simulated and the payload as recorded, drawn
/// as a ghost, and the heights and position error of trajectory.csv for the plot.
/// @throws InputError naming the file, the line and what was expected
nlohmann::json viewData(const ViewOptions& options, std::vector<std::string>& warnings);

/// The page for `data` (viewData), with `three_js` (the library's source) inlined.
std::string viewHtml(const nlohmann::json& data, const std::string& three_js);

/// viewData then viewHtml, written to `path`.
/// @throws InputError when a file cannot be read or written
void writeViewHtml(const ViewOptions& options, const std::string& path,
                   std::vector<std::string>& warnings);

}  // namespace vcontact::report
