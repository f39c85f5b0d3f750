#pragma once
// The one interface every real-time technique implements, and the registry that lists them.
//
// A technique lives in realtime/techniques/<name>/ (C++ and GLSL side by side, a
// <name>_shared.h for structs both sides read) and is added to the registry with one line in
// techniques/registry.cpp. It is created from the scene and its parameter values, records one
// frame at a time into a command buffer, brackets each of its passes with the GPU timer, and
// exposes RGBA32F output images: "" (beauty R,G,B), "direct", "indirect" and any extra layers.
// A GI technique implements only its indirect light (IndirectLight in passes/deferred_gi.h);
// the deferred frame records the shared steps around it.

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include <nlohmann/json.hpp>

#include "giq/scenes/scene.h"

namespace giq::realtime {

class Context;
class GpuTimer;
class Image;
class SceneGpu;
class ShaderCompiler;

// A tunable knob, so a sweep can enumerate what to vary and within which range.
struct Parameter {
  std::string name;
  double default_value = 0.0;
  double min_value = 0.0;
  double max_value = 0.0;
  bool integer = false;
  std::string description;
};

class ParameterValues {
 public:
  ParameterValues() = default;
  // Defaults, overridden by "name=value" strings; throws InputError (field --param) for an
  // unknown name, a value that is not a number, a non-integer for an integer parameter or a
  // value outside [min, max].
  ParameterValues(const std::vector<Parameter>& declared, const std::vector<std::string>& assignments);
  double get(std::string_view name) const;
  int get_int(std::string_view name) const { return int(get(name)); }
  const std::map<std::string, double, std::less<>>& all() const { return values_; }

 private:
  std::map<std::string, double, std::less<>> values_;
};

struct TechniqueCreateInfo {
  Context& ctx;
  ShaderCompiler& compiler;
  const scenes::Scene& scene;
  const SceneGpu& scene_gpu;
  uint32_t width;
  uint32_t height;
  const ParameterValues& parameters;
};

// What moved in the scene since the technique's previous frame. A technique lives for a whole
// sequence: the SceneGpu it was created with is updated in place before each render() (same
// buffer handles and sizes, so recorded descriptors stay valid), and the technique drops or
// rebuilds whatever it derived from what moved (accumulated samples, cached shadow maps,
// injected light). Geometry implies that lights may have moved too.
enum class SceneChange { None, Lights, Geometry };

struct FrameInput {
  VkCommandBuffer cmd;
  int frame;                     // frames rendered by this technique so far (0 first)
  const scenes::Camera& camera;  // in the scene's local frame
  GpuTimer& timer;
  const scenes::Scene& scene;    // posed at this frame: lights, cameras and geometry moved
  SceneChange change = SceneChange::None;
};

class Technique {
 public:
  virtual ~Technique() = default;
  // Records one frame; each pass between timer.begin(name) and timer.end() (timings.json
  // lists the passes as the timer recorded them).
  virtual void render(const FrameInput& in) = 0;
  // Output layers after render(): ("", beauty), ("direct", ...), ("indirect", ...), extras.
  virtual std::vector<std::pair<std::string, Image*>> outputs() = 0;
};

// The parameter a speed-for-accuracy sweep varies, and its values from cheapest to best:
// increasing for most knobs (grid size, samples), decreasing for one whose larger values
// cost less (a temporal upscale factor).
struct QualityKnob {
  std::string parameter;
  std::vector<double> values;
};

struct TechniqueInfo {
  std::string name;
  std::string description;
  std::vector<Parameter> parameters;
  QualityKnob quality;
  std::function<std::unique_ptr<Technique>(const TechniqueCreateInfo&)> create;
  // The image carries the light a constant environment sends onto surfaces (not only the
  // background the camera sees); `giq realtime` warns for a scene with an environment when not.
  bool lights_with_environment = false;
};

// Every registered technique, in registration order (techniques/registry.cpp).
const std::vector<TechniqueInfo>& techniques();
// The listing every tool reads (`giq realtime --list --json`): per technique its name,
// description, parameters (name, default, min, max, integer, description) and quality knob.
nlohmann::json techniques_json();
// Throws InputError (field --technique) naming the available techniques.
const TechniqueInfo& find_technique(std::string_view name);

}  // namespace giq::realtime
