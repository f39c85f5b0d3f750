#pragma once
// Internal: the single-image part of score(), also used for the last frame of a sequence.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "giq/image/image.h"
#include "giq/metrics/score.h"

namespace giq::metrics::detail {

// Scores one checked pair; writes maps and the strip into request.out_dir when asked.
nlohmann::json score_image(const image::Image& reference, const std::string& reference_file, const image::Image& test,
                           const std::string& test_file, bool hdr, const ScoreRequest& request);

nlohmann::json score_sequence(const ScoreRequest& request);

// Reads an image file with a clear error, and tells whether it is linear HDR (EXR).
image::Image read_input(const std::string& file);

}  // namespace giq::metrics::detail
