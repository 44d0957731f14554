#pragma once
// The viewer page's script (report/view_html.hpp), kept apart from the page's HTML.

namespace vcontact::report {

/// The JavaScript that builds the scene, the controls and the plot from the embedded data.
const char* viewScript();

}  // namespace vcontact::report
