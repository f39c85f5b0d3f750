// giq.Scene, giq.reference, giq.realtime and giq.techniques: the renders of giq reference and
// giq realtime, returned as arrays instead of files.

#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <mutex>
#include <optional>
#include <sstream>

#include "arrays.h"
#include "giq/base/error.h"
#include "giq/scenes/scene.h"
#include "interruptible.h"
#include "module.h"
#include "scene_description.h"
#include "scene_setup.h"
#ifdef GIQ_WITH_REFERENCE
#include "giq/reference/progressive_render.h"
#include "giq/reference/reference_exr.h"
#include "reference_frame.h"
#endif
#ifdef GIQ_WITH_VULKAN
#include "giq/realtime/context.h"
#include "giq/realtime/renderer.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/technique.h"
#endif

namespace giq::python {
namespace {

// A loaded scene, with the --sun and --env of the command line applied.
struct Scene {
  std::string path;
  std::shared_ptr<const scenes::Scene> scene;
};

// "eye=0,1,3 target=0,1,0" or ["eye=0,1,3", "target=0,1,0"]: the words of an option.
std::vector<std::string> words_of(const py::object& o, const std::string& field) {
  if (o.is_none()) return {};
  if (py::isinstance<py::str>(o)) {
    std::istringstream in(o.cast<std::string>());
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    return words;
  }
  try {
    return o.cast<std::vector<std::string>>();
  } catch (const py::cast_error&) {
    throw InputError("", field, "expected a string such as 'eye=0,1,3 target=0,1,0 fov=40', or a list of such words");
  }
}

Scene load_scene(const std::filesystem::path& path, const py::object& sun, const py::object& env) {
  cli::SceneSetup setup;
  setup.sun = words_of(sun, "sun");
  // env: a path, a radiance (one number or r, g, b), as --env takes them.
  if (is_path(env)) {
    setup.env = path_of(env);
  } else if (py::isinstance<py::list>(env) || py::isinstance<py::tuple>(env)) {
    for (const py::handle v : env) setup.env += (setup.env.empty() ? "" : ",") + py::repr(py::float_(py::reinterpret_borrow<py::object>(v))).cast<std::string>();
  } else if (!env.is_none()) {
    setup.env = py::repr(py::float_(env)).cast<std::string>();
  }
  py::gil_scoped_release release;
  return {path.string(), std::make_shared<const scenes::Scene>(setup.load(path, 1.0))};
}

// The scene argument: a giq.Scene or a path.
Scene scene_of(const py::object& o) {
  if (py::isinstance<Scene>(o)) return o.cast<Scene>();
  return load_scene(path_of(o), py::none(), py::none());
}

// The scene with the camera= view added (for an image of this aspect), or as it is.
std::shared_ptr<const scenes::Scene> with_camera(const Scene& s, const std::vector<std::string>& camera, double aspect) {
  if (camera.empty()) return s.scene;
  auto copy = std::make_shared<scenes::Scene>(*s.scene);
  scenes::View view;
  view.name = cli::kCameraView;
  view.camera = cli::camera_from_arguments(camera, *copy, aspect);
  copy->add_view(view);
  return copy;
}

void check_size(int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw InputError("", "width/height", std::to_string(width) + "x" + std::to_string(height) + "; expected 1 to 16384 pixels each");
}

#ifdef GIQ_WITH_REFERENCE
py::object reference(const py::object& scene_arg, const std::optional<std::string>& view, const py::object& camera_arg,
                     uint32_t spp, double rel_error, double seconds, int frame, int width, int height, uint64_t seed,
                     int max_bounces, int threads, const std::optional<py::function>& progress) {
  const Scene s = scene_of(scene_arg);
  const std::vector<std::string> camera = words_of(camera_arg, "camera");
  if (view && !camera.empty()) throw InputError("", "view/camera", "give a view or a camera, not both");
  check_size(width, height);
  if (spp == 0 && !(rel_error > 0.0) && !(seconds > 0.0))
    throw InputError("", "spp/rel_error/seconds", "no stopping criterion; give spp, rel_error or seconds");
  if (!(rel_error >= 0.0) || !(seconds >= 0.0) || !std::isfinite(rel_error) || !std::isfinite(seconds))
    throw InputError("", "rel_error/seconds", "must be positive numbers");
  if (frame < 0 || frame >= s.scene->sequence.frames)
    throw InputError(s.path, "frame", std::to_string(frame) + " is outside the scene's sequence 0 to " +
                                          std::to_string(s.scene->sequence.frames - 1));
  reference::RenderSettings settings;
  settings.width = width, settings.height = height, settings.seed = seed;
  settings.max_bounces = max_bounces, settings.threads = threads;
  const auto scene = with_camera(s, camera, double(width) / double(height));
  const cli::ReferenceFrame job = cli::reference_frame(*scene, s.path, view.value_or(""), camera, frame, settings);
  std::mutex m;
  std::optional<reference::Progress> latest;
  image::Image img;
  run_interruptible(
      [&](const std::atomic<bool>& cancel) {
        const reference::Renderer renderer(job.posed, job.metadata.camera, settings);
        reference::ProgressiveOptions po;
        po.stop = {spp, seconds, rel_error};
        po.cancel = &cancel;
        po.on_progress = [&](const reference::Progress& p) {
          std::lock_guard lock(m);
          latest = p;
        };
        const reference::RenderOutcome r = reference::render_progressive(renderer, po);
        if (!r.completed) throw Cancelled{};
        img = reference::reference_image(r.film, settings, job.metadata);
      },
      [&] {
        std::optional<reference::Progress> p;
        {
          std::lock_guard lock(m);
          p.swap(latest);
        }
        if (p && progress) {
          py::dict d;
          d["spp"] = p->spp, d["target_spp"] = p->target_spp, d["elapsed_seconds"] = p->elapsed_seconds;
          d["eta_seconds"] = p->eta_seconds, d["rel_error"] = p->rel_error;
          (*progress)(d);
        }
      });
  return layers_object(img);
}
#endif

#ifdef GIQ_WITH_VULKAN
py::tuple realtime(const py::object& scene_arg, const std::string& technique, const py::object& params, const py::object& frames,
                   int warmup, const std::optional<std::string>& view, const py::object& camera_arg, int width, int height,
                   const std::string& device, bool validation, const std::optional<py::function>& progress) {
  const Scene s = scene_of(scene_arg);
  const std::vector<std::string> camera = words_of(camera_arg, "camera");
  if (view && !camera.empty()) throw InputError("", "view/camera", "give a view or a camera, not both");
  check_size(width, height);
  realtime::RenderOptions o;
  o.technique = technique;
  // {"name": value} or ["name=value", ...], as --param takes them.
  if (py::isinstance<py::dict>(params)) {
    for (const auto& [k, v] : params.cast<py::dict>())
      o.parameters.push_back(py::str(k).cast<std::string>() + "=" + py::str(v).cast<std::string>());
  } else if (!params.is_none()) {
    o.parameters = words_of(params, "params");
  }
  o.view = !camera.empty() ? cli::kCameraView : view.value_or("0");
  o.width = uint32_t(width), o.height = uint32_t(height);
  // frames=N: N measured frames after warmup; frames=(a, b): frames a..b after a warm-up frames.
  if (py::isinstance<py::tuple>(frames) || py::isinstance<py::list>(frames)) {
    const auto [a, b] = frames.cast<std::pair<int, int>>();
    if (a < 0 || b < a) throw InputError("", "frames", "(" + std::to_string(a) + ", " + std::to_string(b) + "); expected (a, b) with 0 <= a <= b");
    if (warmup != 0) throw InputError("", "warmup", "frames=(a, b) already renders frames 0..a-1 as warm-up; give frames=N with warmup");
    o.warmup = a, o.frames = b - a + 1;
  } else {
    o.frames = frames.cast<int>();
    if (o.frames < 1 || o.frames > 1000000) throw InputError("", "frames", std::to_string(o.frames) + "; expected 1 or more measured frames");
    if (warmup < 0) throw InputError("", "warmup", std::to_string(warmup) + "; expected 0 or more frames");
    o.warmup = warmup;
  }
  const auto scene = with_camera(s, camera, double(width) / double(height));
  std::mutex m;
  int done = -2;
  std::vector<image::Image> images;
  nlohmann::json timings;
  std::vector<std::string> messages;
  run_interruptible(
      [&](const std::atomic<bool>& cancel) {
        realtime::ContextOptions co;
        co.device = device;
        co.validation = validation || realtime::ContextOptions::default_validation();
        realtime::Context ctx(co);
        realtime::ShaderCompiler compiler;
        o.on_progress = [&](int n) {
          if (cancel) throw Cancelled{};
          std::lock_guard lock(m);
          done = n;
        };
        timings = realtime::render_sequence(ctx, compiler, *scene, o, [&](realtime::RenderedFrame& f) {
          images.push_back(std::move(f.image));
        });
        messages = ctx.validation_messages();
      },
      [&, last = -2]() mutable {
        int n;
        {
          std::lock_guard lock(m);
          n = done;
        }
        if (progress && n >= 0 && n != last) (*progress)(n, o.warmup + o.frames);
        last = n;
      });
  // Validation errors mean the numbers cannot be trusted (giq realtime exits 3).
  if (!messages.empty()) {
    std::string all;
    for (const auto& msg : messages) all += "\n" + msg;
    throw std::runtime_error("Vulkan validation reported " + std::to_string(messages.size()) + " message(s):" + all);
  }
  py::list out;
  for (const image::Image& img : images) out.append(layers_object(img));
  return py::make_tuple(out, to_python(timings));
}
#endif

}  // namespace

void register_rendering(py::module_& m) {
  py::class_<Scene>(m, "Scene", "A glTF 2.0 scene as giq loads it (docs/scene-format.md).")
      .def(py::init(&load_scene), py::arg("path"), py::kw_only(), py::arg("sun") = py::none(), py::arg("env") = py::none(),
           "Loads a .gltf/.glb. sun: 'dir=x,y,z illuminance=E [color=r,g,b]' adds a directional light; env: radiance\n"
           "r,g,b (or one number) or an equirectangular map's path, as giq's --sun and --env.")
      .def_property_readonly("path", [](const Scene& s) { return s.path; })
      .def_property_readonly("info", [](const Scene& s) { return to_python(cli::describe_scene(*s.scene)); },
                             "What giq scene info --json prints.")
      .def_property_readonly("views",
                             [](const Scene& s) {
                               std::vector<std::string> names;
                               for (const auto& v : s.scene->views) names.push_back(v.name);
                               return names;
                             })
      .def_property_readonly("frames", [](const Scene& s) { return s.scene->sequence.frames; })
      .def_property_readonly("fps", [](const Scene& s) { return s.scene->sequence.fps; })
      .def("__repr__", [](const Scene& s) {
        return "giq.Scene('" + s.path + "', " + std::to_string(s.scene->stats.triangles) + " triangles, " +
               std::to_string(s.scene->views.size()) + " views, " + std::to_string(s.scene->sequence.frames) + " frames)";
      });
#ifdef GIQ_WITH_REFERENCE
  m.def("reference", &reference, py::arg("scene"), py::kw_only(), py::arg("view") = py::none(), py::arg("camera") = py::none(),
        py::arg("spp") = 0, py::arg("rel_error") = 0.0, py::arg("seconds") = 0.0, py::arg("frame") = 0, py::arg("width") = 256,
        py::arg("height") = 256, py::arg("seed") = 0, py::arg("max_bounces") = 64, py::arg("threads") = 0,
        py::arg("progress") = py::none(),
        R"(Renders the path-traced reference of a view, as giq reference does (the same settings give the same bits):
a giq.Layers of (H, W, 3) and (H, W) arrays with the EXR header as .metadata. scene: a giq.Scene or a path.
camera: 'eye=x,y,z target=x,y,z fov=deg ...' as giq's --camera. Stops at spp, rel_error or seconds, whichever
comes first. progress(dict) is called with spp, target_spp, elapsed_seconds, eta_seconds and rel_error.)");
#endif
#ifdef GIQ_WITH_VULKAN
  m.def("realtime", &realtime, py::arg("scene"), py::arg("technique") = "direct", py::kw_only(), py::arg("params") = py::none(),
        py::arg("frames") = 1, py::arg("warmup") = 0, py::arg("view") = py::none(), py::arg("camera") = py::none(),
        py::arg("width") = 256, py::arg("height") = 256, py::arg("device") = "", py::arg("validation") = false,
        py::arg("progress") = py::none(),
        R"(Renders a view with a real-time technique, as giq realtime does: ([giq.Layers per measured frame], timings).
params: {"name": value} or ["name=value"]. frames: N measured frames after warmup, or (a, b) for frames a..b of
the sequence after a warm-up frames. timings: what timings.json holds. progress(frames_done, total).)");
  m.def("techniques", [] { return to_python(realtime::techniques_json()); },
        "The registered techniques, their parameters and quality knobs: what giq realtime --list --json prints.");
#endif
}

}  // namespace giq::python
