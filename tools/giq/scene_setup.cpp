#include "scene_setup.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "giq/base/error.h"
#include "giq/base/hash.h"
#include "giq/image/io.h"

namespace giq::cli {
namespace {

namespace sc = giq::scenes;

struct KeyValue {
  std::string key, value;
};

KeyValue split(const std::string& arg) {
  const size_t eq = arg.find('=');
  return {arg.substr(0, eq), eq == std::string::npos ? "" : arg.substr(eq + 1)};
}

glm::dvec3 parse_vec3(const std::string& option, const std::string& key, const std::string& text) {
  glm::dvec3 v;
  char tail;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v.x, &v.y, &v.z, &tail) != 3 || !std::isfinite(v.x) ||
      !std::isfinite(v.y) || !std::isfinite(v.z))
    throw InputError("", option, key + "=" + text + " is not three finite numbers x,y,z");
  return v;
}

double parse_number(const std::string& option, const std::string& key, const std::string& text, double lo, double hi,
                    const std::string& expected) {
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(x >= lo && x <= hi)) throw InputError("", option, key + "=" + text + " must be " + expected);
  return x;
}

// fov= (vertical) or hfov= (horizontal), in degrees.
double parse_fov(const std::string& key, const std::string& value) {
  const std::string what = key == "hfov" ? "a horizontal" : "a vertical";
  char* end = nullptr;
  const double fov = std::strtod(value.c_str(), &end);
  if (value.empty() || end == value.c_str() || *end != '\0')
    throw InputError("", "--camera", key + "=" + value + " is not a number; give " + what +
                                         " field of view in degrees as a plain number, e.g. " + key + "=39");
  if (!(fov > 0.0 && fov < 180.0))
    throw InputError("", "--camera", key + "=" + value + " must be " + what + " field of view in degrees, in (0, 180)");
  return fov;
}

// An engine's world frame (docs/own-engine.md, "Cameras"): a point or direction given in it
// becomes glTF's (right-handed, +Y up) by to_gltf, and its length unit metres by `metres`.
struct EngineFrame {
  const char* name;
  glm::dmat3 to_gltf;  // columns: where the engine's x, y and z axes go
  double metres;       // its default length unit, in metres
};
const EngineFrame kFrames[] = {
    {"gltf", glm::dmat3(1.0), 1.0},
    {"godot", glm::dmat3(1.0), 1.0},
    // Left-handed, Y up, Z forward: (x, y, z) -> (x, y, -z).
    {"unity", glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1)), 1.0},
    // Left-handed, Z up, X forward, Y right, centimetres: (x, y, z) -> (y, z, -x).
    {"unreal", glm::dmat3(glm::dvec3(0, 0, -1), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)), 0.01},
};

const EngineFrame& parse_frame(const std::string& key, const std::string& value) {
  if (key == "handedness") {
    if (value == "right") return kFrames[0];
    if (value == "left") return kFrames[2];
    throw InputError("", "--camera", "handedness=" + value +
                                         " must be right (glTF, Godot) or left (Y up, as Unity; for Unreal's Z up give frame=unreal)");
  }
  for (const EngineFrame& f : kFrames)
    if (value == f.name) return f;
  throw InputError("", "--camera", "frame=" + value + " must be gltf, godot, unity or unreal");
}

double parse_units(const std::string& value) {
  if (value == "m") return 1.0;
  if (value == "cm") return 0.01;
  if (value == "mm") return 0.001;
  if (value == "in") return 0.0254;
  if (value == "ft") return 0.3048;
  throw InputError("", "--camera", "units=" + value + " must be m, cm, mm, in or ft (the unit of eye= and target=)");
}


sc::Camera look_at(glm::dvec3 eye, glm::dvec3 target, glm::dvec3 up, double fov_deg, const sc::Scene& scene) {
  try {
    return sc::Camera::look_at(glm::vec3(eye - scene.origin), glm::vec3(target - scene.origin), glm::vec3(up),
                               float(fov_deg * std::numbers::pi / 180.0));
  } catch (const std::invalid_argument& e) {
    throw InputError("", "--camera", e.what());
  }
}

// --camera auto: the bounds' sphere seen whole from the front (+Z, the way glTF assets face),
// 20 degrees above the horizon.
sc::Camera auto_camera(const std::vector<std::string>& args, const sc::Scene& scene) {
  double fov = 45.0;
  for (size_t i = 1; i < args.size(); ++i) {
    const KeyValue kv = split(args[i]);
    if (kv.key != "fov") throw InputError("", "--camera", "'" + args[i] + "' is not fov=deg; after 'auto' only fov may follow");
    fov = parse_fov("fov", kv.value);
  }
  if (scene.bounds.empty()) throw InputError(scene.path.string(), "--camera", "auto needs geometry to frame; the scene has none");
  // The bounds are in the scene's local frame; the camera is given in the world's.
  const sc::Framing f = sc::frame_bounds(scene.bounds, fov * std::numbers::pi / 180.0);
  const glm::dvec3 eye = scene.origin + f.eye, centre = scene.origin + f.target;
  std::fprintf(stderr, "giq: --camera auto: eye=%.6g,%.6g,%.6g target=%.6g,%.6g,%.6g fov=%.6g\n", eye.x, eye.y, eye.z, centre.x,
               centre.y, centre.z, fov);
  return look_at(eye, centre, glm::dvec3(0.0, 1.0, 0.0), fov, scene);
}

sc::Camera parse_camera(const std::vector<std::string>& args, const sc::Scene& scene, double aspect) {
  if (args.front() == "auto") return auto_camera(args, scene);
  glm::dvec3 eye, target, up(0.0, 1.0, 0.0);
  double fov = 45.0, hfov = 0.0, ymag = 0.0, units = 0.0;
  bool has_eye = false, has_target = false, has_up = false, has_fov = false;
  const EngineFrame* frame = &kFrames[0];
  std::string frame_key;
  for (const std::string& a : args) {
    const KeyValue kv = split(a);
    if (kv.key == "eye") eye = parse_vec3("--camera", kv.key, kv.value), has_eye = true;
    else if (kv.key == "target") target = parse_vec3("--camera", kv.key, kv.value), has_target = true;
    else if (kv.key == "up") up = parse_vec3("--camera", kv.key, kv.value), has_up = true;
    else if (kv.key == "fov") fov = parse_fov("fov", kv.value), has_fov = true;
    else if (kv.key == "hfov") hfov = parse_fov("hfov", kv.value);
    else if (kv.key == "units") units = parse_units(kv.value);
    else if (kv.key == "frame" || kv.key == "handedness") {
      if (!frame_key.empty()) throw InputError("", "--camera", "give one of frame= and handedness=, once");
      frame = &parse_frame(kv.key, kv.value), frame_key = kv.key;
    } else if (kv.key == "ymag") {
      ymag = parse_number("--camera", "ymag", kv.value, 0.0, 1e30, "an orthographic half height, > 0");
      if (!(ymag > 0.0)) throw InputError("", "--camera", "ymag=" + kv.value + " must be an orthographic half height, > 0");
    } else {
      throw InputError("", "--camera",
                       "'" + a + "' is not one of eye=x,y,z target=x,y,z up=x,y,z fov=deg hfov=deg ymag=m "
                                 "frame=gltf|godot|unity|unreal handedness=right|left units=m|cm|mm|in|ft, or auto");
    }
  }
  if (!has_eye || !has_target) throw InputError("", "--camera", "needs both eye=x,y,z and target=x,y,z, or auto");
  if (has_fov && hfov > 0.0) throw InputError("", "--camera", "fov= (vertical) and hfov= (horizontal) exclude each other; give one");
  if ((has_fov || hfov > 0.0) && ymag > 0.0)
    throw InputError("", "--camera", "a field of view (perspective) and ymag= (orthographic) exclude each other; give one");
  if (eye == target) throw InputError("", "--camera", "eye and target are the same point; the camera needs a direction to look in");
  // The engine's frame and unit to glTF's metres; its up axis unless up= is given.
  const double scale = units > 0.0 ? units : frame->metres;
  eye = frame->to_gltf * eye * scale;
  target = frame->to_gltf * target * scale;
  up = has_up ? frame->to_gltf * up : glm::dvec3(0.0, 1.0, 0.0);
  // The vertical field of view with the horizontal one at the image's aspect ratio.
  if (hfov > 0.0) fov = 2.0 * std::atan(std::tan(0.5 * hfov * std::numbers::pi / 180.0) / aspect) * 180.0 / std::numbers::pi;
  sc::Camera c = look_at(eye, target, up, fov, scene);
  c.ymag = float(ymag * scale);
  return c;
}

sc::Light parse_sun(const std::vector<std::string>& args) {
  sc::Light sun;
  sun.name = "sun";
  sun.type = sc::LightType::Directional;
  bool has_dir = false, has_illuminance = false;
  for (const std::string& a : args) {
    const KeyValue kv = split(a);
    if (kv.key == "dir") {
      const glm::dvec3 d = parse_vec3("--sun", kv.key, kv.value);
      if (!(glm::length(d) > 0.0)) throw InputError("", "--sun", "dir=" + kv.value + " must not be zero");
      sun.direction = glm::vec3(glm::normalize(d)), has_dir = true;
    } else if (kv.key == "illuminance") {
      sun.intensity = float(parse_number("--sun", kv.key, kv.value, 0.0, 1e30, "a non-negative number (irradiance on a surface facing the sun)"));
      has_illuminance = true;
    } else if (kv.key == "color") {
      const glm::dvec3 c = parse_vec3("--sun", kv.key, kv.value);
      if (c.x < 0.0 || c.y < 0.0 || c.z < 0.0) throw InputError("", "--sun", "color=" + kv.value + " must not be negative");
      sun.color = glm::vec3(c);
    } else {
      throw InputError("", "--sun", "'" + a + "' is not one of dir=x,y,z illuminance=E color=r,g,b");
    }
  }
  if (!has_dir || !has_illuminance) throw InputError("", "--sun", "needs both dir=x,y,z (the way the light travels) and illuminance=E");
  return sun;
}

glm::vec3 parse_env(const std::string& text) {
  glm::dvec3 v;
  char tail;
  const int n = std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v.x, &v.y, &v.z, &tail);
  if (n == 1 && text.find(',') == std::string::npos) v = glm::dvec3(v.x);
  else if (n != 3) throw InputError("", "--env", "'" + text + "' is not a radiance r,g,b or one number");
  if (!(v.x >= 0.0 && v.y >= 0.0 && v.z >= 0.0 && v.x < 1e30 && v.y < 1e30 && v.z < 1e30))
    throw InputError("", "--env", "'" + text + "' must be finite and not negative");
  return glm::vec3(v);
}

// An equirectangular HDR map (OpenEXR, Radiance .hdr, or any format giq reads) as RGB
// radiance: every pixel finite and not negative, at least 2 x 1 pixels.
struct EnvironmentMap {
  int width = 0, height = 0;
  std::vector<glm::vec3> radiance;
  std::string hash;
};
EnvironmentMap read_environment_map(const std::string& path) {
  const image::Image img = image::read_image(path);
  EnvironmentMap m;
  m.width = img.width(), m.height = img.height();
  if (m.width < 2 || m.height < 1 || m.width > 16384 || m.height > 16384)
    throw InputError(path, "--env", std::to_string(m.width) + "x" + std::to_string(m.height) + " map; expected 2 to 16384 pixels wide and 1 to 16384 high");
  for (const char* c : {"R", "G", "B"})
    if (!img.has_channel(c)) throw InputError(path, "--env", std::string("no ") + c + " channel; expected an RGB radiance map");
  const float *r = img.channel("R"), *g = img.channel("G"), *b = img.channel("B");
  Hasher h;
  m.radiance.resize(img.pixel_count());
  for (size_t i = 0; i < img.pixel_count(); ++i) {
    const glm::vec3 v(r[i], g[i], b[i]);
    if (!(v.r >= 0.0f && v.g >= 0.0f && v.b >= 0.0f && v.r < 3e38f && v.g < 3e38f && v.b < 3e38f))
      throw InputError(path, "--env", "pixel (" + std::to_string(i % size_t(m.width)) + ", " + std::to_string(i / size_t(m.width)) +
                                           ") is not a finite, non-negative radiance");
    m.radiance[i] = v;
  }
  h.add(m.radiance.data(), m.radiance.size() * sizeof(glm::vec3));
  if (m.width != 2 * m.height)
    std::fprintf(stderr, "giq: warning: %s: %dx%d environment map; an equirectangular map is twice as wide as high, so this one is "
                 "stretched\n", path.c_str(), m.width, m.height);
  m.hash = h.hex();
  return m;
}

bool looks_like_numbers(const std::string& text) {
  return !text.empty() && text.find_first_not_of("0123456789.,+-eE") == std::string::npos;
}

}  // namespace

void SceneSetup::add_options(CLI::App& cmd) {
  cmd.add_option("--camera", camera,
                 "Camera in world coordinates: eye=x,y,z target=x,y,z [up=x,y,z] [fov=deg (vertical) | hfov=deg | "
                 "ymag=m (orthographic, half height)] [frame=gltf|godot|unity|unreal | handedness=right|left] "
                 "[units=m|cm|mm|in|ft], or auto [fov=deg] (docs/own-engine.md)")
      ->expected(1, 8);
  cmd.add_option("--sun", sun, "Add a directional light: dir=x,y,z (the way it travels) illuminance=E [color=r,g,b]")->expected(2, 3);
  cmd.add_option("--env", env, "Environment replacing the scene's: a constant radiance r,g,b (or one number), or an equirectangular map FILE (.exr, .hdr; +Y up, -Z at the centre)");
}

sc::Scene SceneSetup::load(const std::filesystem::path& path, double aspect) const {
  sc::Scene scene = sc::load(path);
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "giq: warning: %s: %s\n", path.string().c_str(), w.c_str());
  // Described by the parsed values, so that two spellings of one light name the same scene.
  auto numbers = [](std::initializer_list<float> v) {
    std::string out;
    char b[32];
    for (float x : v) std::snprintf(b, sizeof b, "%s%.9g", out.empty() ? "" : ",", double(x)), out += b;
    return out;
  };
  if (!sun.empty()) {
    const sc::Light l = parse_sun(sun);
    scene.add_light(l, "sun dir=" + numbers({l.direction.x, l.direction.y, l.direction.z}) + " illuminance=" +
                           numbers({l.intensity}) + " color=" + numbers({l.color.r, l.color.g, l.color.b}));
  }
  if (!env.empty() && !looks_like_numbers(env)) {
    const EnvironmentMap m = read_environment_map(env);
    scene.set_environment_map(m.width, m.height, m.radiance, "env map " + m.hash);
  } else if (!env.empty()) {
    const glm::vec3 e = parse_env(env);
    scene.set_environment(e, "env " + numbers({e.r, e.g, e.b}));
  }
  if (scene.stats.total_light_power <= 0.0 && scene.environment == glm::vec3(0.0f))
    throw InputError(path.string(), "lights",
                     "the scene has no light (no punctual light, no emissive material, no environment, or all of zero "
                     "strength), so every image of it is black; add one with --sun dir=x,y,z illuminance=E or --env r,g,b");
  if (!camera.empty()) {
    sc::View view;
    view.name = kCameraView;
    view.camera = camera_from_arguments(camera, scene, aspect);
    scene.add_view(view);
  }
  return scene;
}

scenes::Camera camera_from_arguments(const std::vector<std::string>& camera, const scenes::Scene& scene, double aspect) {
  // One quoted argument ("eye=.. target=.. fov=..", as configs and scripts pass it) reads
  // like the same words given separately.
  std::vector<std::string> words;
  for (const std::string& a : camera) {
    std::istringstream in(a);
    for (std::string w; in >> w;) words.push_back(w);
  }
  if (words.empty()) throw InputError("", "--camera", "is empty; expected eye=x,y,z target=x,y,z [fov=deg] or auto");
  return parse_camera(words, scene, aspect);
}

bool warn_if_black(const image::Image& image, const std::string& what) {
  if (!image.has_layer("")) return false;
  const auto names = image.layer_channels("");
  for (const auto& n : names) {
    const float* c = image.channel(n);
    for (size_t i = 0; i < image.pixel_count(); ++i)
      if (std::isfinite(c[i]) && c[i] != 0.0f) return false;
  }
  std::fprintf(stderr,
               "giq: warning: %s is black in every pixel. Likely causes: the camera looks away from the scene or sits "
               "inside a closed mesh (check eye= and target=; an engine's coordinates need frame=unity|unreal or "
               "handedness=left, and its units units=cm|mm: docs/own-engine.md), the lights are blocked or behind "
               "one-sided surfaces, or the view sees only the back of one-sided surfaces\n",
               what.c_str());
  return true;
}

}  // namespace giq::cli
