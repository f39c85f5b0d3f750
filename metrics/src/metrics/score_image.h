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

// An input as the metrics see it (score_input.cpp): read with a clear error, its compared
// layer (the request's layer, or test_layer for the test) under the reference layer's channel
// names, with the reference's variance layer for it and its objectId; cropped, the test's
// 8-bit encoding read as asked, the display transform applied to the reference and to an HDR
// test; every other channel (alpha included) dropped.
enum class Side { Reference, Test };
image::Image read_input(const std::string& file, Side side, const ScoreRequest& request);
// Whether the pair is compared as HDR (HDR-FLIP): both files EXR and no tone curve making
// them display-referred.
bool compares_hdr(const std::string& reference_file, const std::string& test_file, const ScoreRequest& request);

}  // namespace giq::metrics::detail
