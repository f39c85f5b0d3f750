// `giq realtime`: renders a scene's view with a real-time technique on a Vulkan device,
// headless, writing one multi-layer EXR per measured frame and timings.json.

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "command.h"
#include "integer_check.h"
#include "progress.h"
#include "scene_setup.h"
#include "output_guard.h"
#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "giq/base/frames.h"
#include "giq/image/io.h"
#include "giq/realtime/context.h"
#include "giq/realtime/renderer.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/technique.h"
#include "giq/scenes/scene.h"

namespace giq::cli {
namespace {

namespace fs = std::filesystem;
namespace rt = giq::realtime;

struct RealtimeArgs {
  std::string scene;
  std::string view = "0";
  CLI::Option* view_option = nullptr;
  SceneSetup setup;  // --camera, --sun, --env
  std::string technique = "direct";
  std::vector<std::string> params;
  std::string frames = "1";
  int warmup = -1;  // -1: not given
  uint32_t width = 256;
  uint32_t height = 256;
  std::string device;
  std::string out;
  bool list = false;
  bool json = false;
  bool list_devices = false;
  bool validation = false;
  bool no_images = false;
};

void print_techniques() {
  for (const auto& t : rt::techniques()) {
    std::printf("%s\n    %s\n", t.name.c_str(), t.description.c_str());
    for (const auto& p : t.parameters)
      std::printf("    --param %s=%.10g   [%.10g, %.10g]%s  %s\n", p.name.c_str(), p.default_value, p.min_value, p.max_value,
                  p.integer ? " integer" : "", p.description.c_str());
    std::string values;
    for (double v : t.quality.values) {
      char number[32];
      std::snprintf(number, sizeof number, "%.10g", v);
      values += (values.empty() ? "" : ",") + std::string(number);
    }
    std::printf("    quality knob: %s=%s\n", t.quality.parameter.c_str(), values.c_str());
  }
}

void print_devices() {
  for (const auto& d : rt::Context::enumerate_devices())
    std::printf("%u  %s  (%s; %s)%s\n", d.index, d.name.c_str(), d.type.c_str(), d.driver.c_str(),
                d.usable ? "" : ("  unusable: " + d.unusable_reason).c_str());
}

// A scene argument is a path; a bare name ("cornell") also finds scenes/<name>.gltf.
fs::path resolve_scene(const std::string& s) {
  const fs::path p(s);
  if (fs::exists(p) || p.has_extension() || p.has_parent_path()) return p;
  for (const fs::path& c : {fs::path("scenes") / (s + ".gltf"), fs::path(s + ".gltf")})
    if (fs::exists(c)) return c;
  return p;
}

int run(const RealtimeArgs& a) {
  if (a.list) {
    if (a.json)
      std::printf("%s\n", rt::techniques_json().dump(2).c_str());
    else
      print_techniques();
    return 0;
  }
  if (a.list_devices) {
    print_devices();
    return 0;
  }
  if (a.scene.empty()) throw InputError("", "--scene", "a scene is required (a .gltf/.glb path)");
  if (a.out.empty()) throw InputError("", "--out", "an output folder is required");
  if (a.setup.has_camera() && a.view_option->count() > 0) throw InputError("", "--view/--camera", "give a view or a camera, not both");
  const scenes::Scene scene = a.setup.load(resolve_scene(a.scene), double(a.width) / double(a.height));
  if (const rt::TechniqueInfo& info = rt::find_technique(a.technique); scene.features.environment && !info.lights_with_environment)
    std::fprintf(stderr,
                 "giq: warning: %s: technique %s does not light surfaces with the environment (it shows it as background "
                 "only); the reference does, and the difference counts as error\n",
                 scene.path.string().c_str(), a.technique.c_str());
  rt::ContextOptions co;
  co.device = a.device;
  co.validation = a.validation || rt::ContextOptions::default_validation();
  rt::Context ctx(co);
  rt::ShaderCompiler compiler;
  rt::RenderOptions o;
  o.technique = a.technique;
  o.parameters = a.params;
  o.view = a.setup.has_camera() ? kCameraView : a.view;
  o.width = a.width;
  o.height = a.height;
  // --frames N: N measured frames after --warmup W; --frames A:B: frames A..B of the sequence,
  // the A before them rendered as warm-up (the grammar of every other command's --frames).
  if (const auto range = parse_frame_range(a.frames)) {
    if (a.warmup >= 0)
      throw InputError("", "--warmup", "--frames " + a.frames + " already renders frames 0.." + std::to_string(range->first - 1) +
                                           " as warm-up; give --frames N with --warmup W, or A:B alone");
    o.warmup = range->first;
    o.frames = range->second - range->first + 1;
  } else {
    char* end = nullptr;
    const long n = std::strtol(a.frames.c_str(), &end, 10);
    if (a.frames.empty() || *end != '\0' || n < 1 || n > 1000000)
      throw InputError("", "--frames", "'" + a.frames + "'; expected a number of measured frames N >= 1, or a range A:B of frames");
    o.frames = int(n);
    o.warmup = std::max(a.warmup, 0);
  }
  o.read_back = !a.no_images;
  const fs::path out(a.out);
  check_output_folder(out, {resolve_scene(a.scene)}, "--out");
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw InputError(out.string(), "--out", "cannot create the folder: " + ec.message());
  // Progress on a terminal: the setup (scene upload, shader compilation), then warm-up and
  // measured frames, with the time left at the mean pace of the frames after the first (which
  // also pays for the pipelines' first use).
  ProgressLine line;
  const auto start = std::chrono::steady_clock::now();
  auto first_done = start;
  if (line.active())
    o.on_progress = [&, total = o.warmup + o.frames](int done) {
      const auto now = std::chrono::steady_clock::now();
      if (done < 0) return line.show("giq realtime: uploading the scene, compiling shaders...");
      if (done == 1) first_done = now;
      const double pace = done > 1 ? std::chrono::duration<double>(now - first_done).count() / (done - 1) : -1.0;
      const int warm = std::min(done, o.warmup);
      line.show("giq realtime: warm-up %d/%d, frames %d/%d  %s elapsed  ETA %s", warm, o.warmup, done - warm, o.frames,
                format_seconds(std::chrono::duration<double>(now - start).count()).c_str(),
                format_seconds(pace < 0.0 ? -1.0 : pace * (total - done)).c_str());
    };
  bool warned_black = false;
  const nlohmann::json timings = rt::render_sequence(ctx, compiler, scene, o, [&](rt::RenderedFrame& f) {
    if (!a.no_images) {
      image::write_exr(f.image, out / frame_file(f.frame));
    }
    if (!warned_black) {
      line.clear();
      warned_black = warn_if_black(f.image, (out / frame_file(f.frame)).string());
    }
  });
  line.finish();
  write_file_atomically(out / "timings.json", timings.dump(2) + "\n");
  const auto messages = ctx.validation_messages();
  for (const auto& m : messages) std::cerr << "giq: validation: " << m << '\n';
  std::printf("giq realtime: %s on %s, %dx%d, %d frames (+%d warm-up): median %.3f ms GPU per frame -> %s\n",
              a.technique.c_str(), ctx.info().name.c_str(), int(a.width), int(a.height), o.frames, o.warmup,
              timings["frame_gpu_ms"].value("median", 0.0), out.string().c_str());
  // Validation errors mean the numbers cannot be trusted: an internal error, not a result.
  return messages.empty() ? 0 : 3;
}

}  // namespace

void add_realtime_command(CLI::App& app, int& exit_code) {
  static RealtimeArgs a;
  auto* cmd = app.add_subcommand("realtime", "Render a view with a real-time technique on a Vulkan device (headless)");
  cmd->add_option("--scene", a.scene, "glTF 2.0 scene (.gltf/.glb), or a built-in scene's name");
  a.view_option = cmd->add_option("--view", a.view, "View name or index")->capture_default_str();
  a.setup.add_options(*cmd);
  cmd->add_option("--technique", a.technique, "Technique (see --list)")->capture_default_str();
  cmd->add_option("--param", a.params, "Technique parameter name=value (repeatable)");
  cmd->add_option("--frames", a.frames,
                  "Measured frames (one EXR each): N after --warmup, or A:B, frames A..B of the sequence after A warm-up frames")
      ->capture_default_str();
  cmd->add_option("--warmup", a.warmup, "Frames rendered before the measured ones, with --frames N (default 0)")
      ->check(integer_in(0.0L, 1000000.0L));
  cmd->add_option("--width", a.width, "Image width")->capture_default_str();
  cmd->add_option("--height", a.height, "Image height")->capture_default_str();
  cmd->add_option("--device", a.device, "Vulkan device: index or part of its name (default: a discrete GPU, else lavapipe)");
  cmd->add_option("--out", a.out, "Output folder for frame_NNNN.exr and timings.json");
  cmd->add_flag("--list", a.list, "List techniques, their parameters and quality knobs");
  cmd->add_flag("--json", a.json, "With --list: the listing as JSON, the form tools read");
  cmd->add_flag("--list-devices", a.list_devices, "List Vulkan devices");
  cmd->add_flag("--validation", a.validation, "Enable the Khronos validation layer (any message makes the run fail)");
  cmd->add_flag("--no-images", a.no_images, "Write timings.json only (benchmarks)");
  cmd->footer(
      "Example: frames 28..43 of a sequence (28 warm-up frames first), as EXRs and timings.json:\n"
      "  giq realtime --scene scenes/movinglight.gltf --technique ddgi --frames 28:43 --out out/ddgi");
  cmd->callback([&exit_code] { exit_code = run(a); });
}

}  // namespace giq::cli
