#include "report/view_html.hpp"

#include <fstream>
#include <sstream>

#include "geometry/error.hpp"
#include "io/json_file.hpp"
#include "io/output_file.hpp"
#include "report/view_html_script.hpp"

namespace vcontact::report {
namespace {

// "</" cannot end the script element early once written "<\/": the same string in JSON and in
// JavaScript string literals, regular expressions and comments.
std::string scriptSafe(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    out.push_back(text[i]);
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out.push_back('\\');
  }
  return out;
}

constexpr const char* kHead = R"HTML(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>vcontact view</title>
<style>
  html, body { margin: 0; height: 100%; font-family: sans-serif; font-size: 14px; }
  body { display: flex; flex-direction: column; }
  #title { padding: 6px 10px; background: #263238; color: #fff; }
  #view { flex: 1 1 auto; min-height: 200px; position: relative; }
  #controls { display: flex; gap: 10px; align-items: center; padding: 6px 10px; background: #eceff1; }
  #slider { flex: 1 1 auto; }
  #clock { font-family: monospace; min-width: 10em; }
  #plot { width: 100%; height: 180px; display: block; }
</style>
</head>
<body>
<div id="title"></div>
<div id="view"></div>
<div id="controls">
  <button id="play">Play</button>
  <input id="slider" type="range" min="0" max="0" step="1" value="0">
  <span id="clock"></span>
  <label>speed <select id="speed"></select></label>
  <label>plot <select id="pair"></select></label>
</div>
<canvas id="plot"></canvas>
)HTML";

}  // namespace

std::string viewHtml(const nlohmann::json& data, const std::string& three_js) {
  std::ostringstream page;
  page << kHead << "<script id=\"vcontact-data\" type=\"application/json\">"
       << scriptSafe(io::jsonText(data, -1)) << "</script>\n<script>\n"
       << scriptSafe(three_js) << "\n</script>\n<script>" << viewScript()
       << "</script>\n</body>\n</html>\n";
  return page.str();
}

void writeViewHtml(const ViewOptions& options, const std::string& path,
                   std::vector<std::string>& warnings) {
  const nlohmann::json data = viewData(options, warnings);
  std::ifstream three(options.three_js);
  if (!three) {
    throw InputError(options.three_js,
                     "cannot read three.js (Debian package libjs-three; scripts/setup.sh "
                     "installs it)");
  }
  std::stringstream library;
  library << three.rdbuf();
  const std::string html = viewHtml(data, library.str());
  io::writeFile(path, [&](std::ostream& out) { out << html; });  // whole or not at all
}

}  // namespace vcontact::report
