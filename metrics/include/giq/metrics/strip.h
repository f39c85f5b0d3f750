#pragma once
// The side-by-side strip PNG for a quick look: reference | technique | error heat map. Each
// panel is box-filtered down to at most `max_panel` pixels on its longer side (so a 16k image
// gives a small file), the two images share one exposure and are sRGB-encoded. HDR input:
// the exposure maps the reference's mean luminance to 0.18 (the photographic middle grey);
// display-referred (LDR) input is shown as it is (exposure 0).

#include <filesystem>

#include "giq/metrics/layer.h"
#include "giq/metrics/maps.h"

namespace giq::metrics {

struct StripInfo {
  int panel_width = 0, panel_height = 0;
  float exposure = 0.0f;  // stops applied to both images
};

StripInfo write_strip(const std::filesystem::path& path, const RgbLayer& reference, const RgbLayer& test,
                      const Map& error, const MapRange& error_range, bool hdr, int max_panel = 1024);

}  // namespace giq::metrics
