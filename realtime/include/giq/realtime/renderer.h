#pragma once
// Runs a technique over a sequence of frames: frame f shows Scene::at_frame(f) through the
// chosen view; the first `warmup` frames are rendered and timed but not reported as
// measured. Produces one multi-layer image per measured frame and the timings.json content.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "giq/image/image.h"
#include "giq/realtime/timer.h"
#include "giq/scenes/scene.h"

namespace giq::realtime {

class Context;
class ShaderCompiler;
class Technique;

struct RenderOptions {
  std::string technique = "direct";
  std::vector<std::string> parameters;  // "name=value"
  std::string view = "0";               // name or index
  uint32_t width = 256;
  uint32_t height = 256;
  int frames = 1;  // measured frames
  int warmup = 0;  // frames rendered before them
  // Read the outputs back and call on_frame with the image; off for benchmarks that only need
  // timings (on_frame then gets an empty image).
  bool read_back = true;
  // For progress displays: called with frames_done = -1 before the scene is uploaded and the
  // technique created (its shaders compiled), then after every frame, warm-up frames
  // included, with frames_done counting them.
  std::function<void(int frames_done)> on_progress;
};

struct RenderedFrame {
  int frame = 0;  // sequence frame index (warm-up frames come first)
  image::Image image;
  FrameTiming timing;
};

// Reads a technique's outputs back: R,G,B and <layer>.R/G/B for every other layer.
image::Image read_outputs(Technique& technique, uint32_t width, uint32_t height);

// Renders warmup + frames frames, calling on_frame for each measured frame, and returns the
// timings.json document (device, resolution, technique, per-pass and per-frame statistics).
// Throws InputError for a bad view, technique, parameter or resolution.
nlohmann::json render_sequence(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& scene,
                               const RenderOptions& options, const std::function<void(RenderedFrame&)>& on_frame);

}  // namespace giq::realtime
