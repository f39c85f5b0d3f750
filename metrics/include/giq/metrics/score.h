#pragma once
// Scoring a technique against the reference: every metric of docs/metrics.md, the maps and the
// strip, and metrics.json, in which every value carries the name of its definition and its
// inputs. `giq score` is a thin layer over this.
//
// Single image: per-image errors, noise floor, SSIM, FLIP (HDR-FLIP for EXR inputs, LDR-FLIP
// otherwise), leaking; maps abs/relative/signed/FLIP/leak (EXR + PNG) and strip.png.
// Sequence (frames A..B): bias^2/variance, flicker, temporal_flip and lag90 over the frames,
// cheap per-frame errors, and the full single-image score of the last frame (with its maps)
// plus the temporal std-dev map. Frames are read one at a time: at most two reference and two
// technique frames are resident.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "giq/image/image.h"
#include "giq/metrics/display.h"
#include "giq/metrics/maps.h"

namespace giq::metrics {

// A region of both images, in pixels from the top-left corner.
struct Crop {
  int x = 0, y = 0, width = 0, height = 0;
};

// How an 8-bit (PNG, JPEG) test image's values are to be read: as sRGB-encoded (decoded to
// linear, the default and what screenshots are) or as linear values stored as they are.
enum class TestEncoding { Srgb, Linear };

struct ScoreRequest {
  // Image files, or printf-style patterns with one %d / %0Nd for sequences. A reference without
  // a pattern stands for every frame (static scene and camera).
  std::string reference;
  std::string test;
  std::optional<std::pair<int, int>> frames;  // A..B inclusive, for patterns
  std::string layer;                          // "" = beauty; the reference's layer
  std::optional<std::string> test_layer;      // the test's, when it differs ("" = beauty)
  // Images from outside giq (docs/own-engine.md): a region of both, the test's 8-bit
  // encoding, and the display transform applied to the reference (and an HDR test).
  std::optional<Crop> crop;
  TestEncoding test_encoding = TestEncoding::Srgb;
  DisplayTransform display;
  std::filesystem::path out_dir;              // metrics.json, maps, strip
  // Leak regions declared by the scene (objectId values) and where they came from.
  std::vector<uint32_t> leak_object_ids;
  std::string scene;
  std::optional<double> frame_ms;  // technique frame time (timings.json frame_ms.median)
  std::string timings;             // the timings file it came from
  std::optional<int> step_frame;   // lag: the frame of the step change (default: detected)
  std::string step_frame_source = "given";  // where step_frame came from, for metrics.json
  bool write_maps = true;
  // Sequences: only the sequence metrics (bias/variance, flicker, lag, per-frame errors),
  // without temporal FLIP and the full score of the last frame (giq.flicker, giq.lag).
  bool sequence_only = false;
};

// Runs everything, writes <out_dir>/metrics.json (atomically) and returns its content.
// Throws InputError for bad input (missing file or layer, size or channel mismatch). A result
// that is probably meaningless (an LDR test against an HDR reference without a tone curve,
// a brightness ratio suggesting an exposure or unit mismatch, a black or too noisy
// reference) is scored anyway and says why in metrics.json's "warnings".
nlohmann::json score(const ScoreRequest& request);

// Images already in memory (the Python module): one image per side, or one per frame (a
// reference of one image stands for every frame). `name`s stand for the files in messages and
// metrics.json; `hdr` says the values are linear radiance, as an EXR's are, rather than
// display-referred, as an 8-bit image's (decoded to linear) are.
struct ImageInputs {
  std::vector<image::Image> reference, test;
  bool sequence = false;  // test holds frames 0..n-1 (even one) rather than one image
  std::string reference_name = "<reference>", test_name = "<test>";
  bool reference_hdr = true, test_hdr = true;
};

struct ScoreResult {
  nlohmann::json metrics;  // what metrics.json holds
  std::vector<Map> maps;   // the single image's (or last frame's) maps, when keep_maps
};

// score() on images in memory: the same checks, metrics and metrics.json, written with the
// maps and strip only when request.out_dir is set (request.reference, .test and .frames are
// ignored: with several test images, the frames are 0..n-1).
ScoreResult score(const ImageInputs& inputs, const ScoreRequest& request, bool keep_maps = false);

// metrics.json's layout version: 2 stores the input paths (inputs.reference, test, scene,
// timings) relative to the file's own folder; 1 stored them as given on the command line.
inline constexpr int kMetricsSchemaVersion = 2;

// `path` as seen from folder `out_dir` (a relative path when one exists, else absolute).
std::string path_from_output(const std::string& path, const std::filesystem::path& out_dir);

// A fixed-width table of the headline values of a metrics.json, for humans.
std::string format_table(const nlohmann::json& metrics);

// The file of frame `frame` of a pattern ("ref_%04d.exr", 7 -> "ref_0007.exr"). Throws
// InputError when the pattern has a conversion other than one %d / %0Nd (or "%%").
std::string frame_path(const std::string& pattern, int frame);
bool is_pattern(const std::string& path);

}  // namespace giq::metrics
