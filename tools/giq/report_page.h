#pragma once
// The HTML page of `giq report`: one self-contained file (images as data URIs, inline CSS and
// a small vanilla script, no network) with the gate table, per scene the reference and each
// technique side by side with synchronised zoom and pan, the error maps with their colour
// scales, a flip-book of sequence frames, the metric tables and the speed/accuracy plots.
// Every string that comes from a file is HTML-escaped.

#include <string>

#include "report_inputs.h"

namespace giq::cli {

std::string report_html(const ReportInputs& inputs, const std::string& title);

// CSS linear-gradient stops of a giq colour map, for the scale under an error map.
std::string colormap_gradient(const std::string& colormap);

}  // namespace giq::cli
