#pragma once
// Internal: the single-image part of score(), also used for the last frame of a sequence.

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "giq/image/image.h"
#include "giq/metrics/maps.h"
#include "giq/metrics/score.h"

namespace giq::metrics::detail {

// Scores one checked pair; writes maps and the strip into request.out_dir when asked, and
// hands the maps to `kept` when given.
nlohmann::json score_image(const image::Image& reference, const std::string& reference_file, const image::Image& test,
                           const std::string& test_file, bool hdr, const ScoreRequest& request,
                           std::vector<Map>* kept = nullptr);

// The frames of a sequence as score_sequence reads them, one at a time: files or images in
// memory, each prepared (prepare_input) on the way.
struct Frames {
  int first = 0, last = 0;
  bool per_frame_reference = true;  // else reference(first) stands for every frame
  bool hdr = true;                  // compared as HDR (compares_hdr)
  std::function<image::Image(int frame)> reference, test;
  std::function<std::string(int frame)> reference_name, test_name;
  std::string reference_label, test_label;  // the whole sequence's, for metrics.json
};
nlohmann::json score_sequence(const Frames& frames, const ScoreRequest& request, std::vector<Map>* kept = nullptr);

// An input as the metrics see it (score_input.cpp): read with a clear error, its compared
// layer (the request's layer, or test_layer for the test) under the reference layer's channel
// names, with the reference's variance layer for it and its objectId; cropped, the test's
// 8-bit encoding read as asked, the display transform applied to the reference and to an HDR
// test; every other channel (alpha included) dropped.
enum class Side { Reference, Test };
image::Image read_input(const std::string& file, Side side, const ScoreRequest& request);
// The same for an image already decoded: `name` stands for its file in messages, `hdr` says
// whether it holds linear values (as an EXR) or display-referred ones (as an 8-bit image).
image::Image prepare_input(const image::Image& image, const std::string& name, bool hdr, Side side,
                           const ScoreRequest& request);
// Whether the pair is compared as HDR (HDR-FLIP): both files EXR and no tone curve making
// them display-referred.
bool compares_hdr(const std::string& reference_file, const std::string& test_file, const ScoreRequest& request);

}  // namespace giq::metrics::detail
