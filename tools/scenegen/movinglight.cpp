// `movinglight`: the Cornell box with its ceiling light off and a point light that circles
// under the ceiling, then jumps (frame 30) and stays, for flicker and lag.

#include <cmath>
#include <numbers>

#include "cornell_box.h"
#include "scenes.h"
#include "text.h"

namespace giq::scenegen {
namespace {

constexpr int kFrames = 60;
constexpr double kFps = 30.0;
constexpr int kLoopFrames = 30;  // one full circle over frames 0..30
const glm::dvec3 kCircleCentre = cornell::mm(278.0, 450.0, 279.6);
constexpr double kCircleRadius = 0.15;
// Where the light jumps to: low, in front of the tall block and 83 mm from the red wall, so
// the red wall and the floor light up and the whole box's indirect light changes at once.
const glm::dvec3 kJumpTarget = cornell::mm(470.0, 120.0, 150.0);
// The jump happens half-way between frames 29 and 30, so no frame time sits on the key
// and every reader's STEP convention gives frame 30 the new position.
constexpr double kJumpTime = (kLoopFrames - 0.5) / kFps;

glm::dvec3 on_circle(int frame) {
  const double angle = 2.0 * std::numbers::pi * frame / kLoopFrames;
  return kCircleCentre + kCircleRadius * glm::dvec3(std::cos(angle), 0.0, std::sin(angle));
}

}  // namespace

BuiltinScene make_movinglight() {
  BuiltinScene s;
  s.name = "movinglight";
  s.purpose =
      "The Cornell box lit by a moving point light instead of its ceiling light, played as a "
      "60-frame sequence at 30 fps: frames 12-27 measure flicker while the light moves, the "
      "jump at frame 30 is the step change whose response measures lag (METRICS.md \"Lag\", "
      "t0 = 30), and frames 30-59 are static so the response can settle (lag over frames "
      "28-59).";
  cornell::add_box(s.gltf, false);

  // Same total power as the `cornell` ceiling light: a one-sided Lambertian emitter of area A
  // and radiance L emits pi A L; an isotropic point light of radiant intensity I emits 4 pi I;
  // so I = A L / 4, per channel.
  const glm::dvec3 extent = cornell::kLightMax - cornell::kLightMin;
  const double area = extent.x * extent.z;
  const glm::dvec3 radiant = area * cornell::kLightRadiance / 4.0;
  const double peak = std::max({radiant.r, radiant.g, radiant.b});

  // The jump is a STEP translation of a parent node and the circle a LINEAR translation of the
  // light itself (one animation may target each node's translation only once).
  const glm::dvec3 jump = kJumpTarget - on_circle(kLoopFrames);
  const int rig = s.gltf.add_group_node("light_rig", {});
  const int light = s.gltf.add_light_node({"moving_light", LightKind::Point, radiant / peak, peak},
                                          {on_circle(0)}, rig);

  TranslationTrack circle{light, Interpolation::Linear, {}, {}};
  for (int k = 0; k <= kLoopFrames; ++k) {
    circle.times.push_back(k / kFps);
    circle.values.push_back(on_circle(k));
  }
  TranslationTrack step{rig, Interpolation::Step, {0.0, kJumpTime}, {glm::dvec3(0.0), jump}};
  const int animation = s.gltf.add_animation("light_path", {circle, step});
  // Flicker while the light circles, after the histories' warm-up (frames 12-27); lag from
  // two frames before the jump to the last frame: nothing moves after it, so every later frame
  // is the settled state the response is measured against.
  s.gltf.set_sequence(kFrames, kFps, animation,
                      GltfWriter::MeasurementWindows{kLoopFrames, {12, kLoopFrames - 3}, {kLoopFrames - 2, kFrames - 1}});

  s.notes = {
      "Geometry, materials and views: those of `cornell` (same code), without the ceiling "
      "light quad.",
      "The point light `moving_light` has the ceiling light's total power: I = A L / 4 per "
      "channel (pi A L is emitted by the one-sided area light of area A = " +
          num(area, 5) + " m^2 and radiance L = " + vec(cornell::kLightRadiance) +
          ", 4 pi I by a point light), so I = " + vec(radiant, 6) + " W/sr.",
      "Path (animation " + std::to_string(animation) + ", `light_path`): over frames 0-" +
          std::to_string(kLoopFrames) + " one circle of radius " + num(kCircleRadius) +
          " m around " + vec(kCircleCentre) + " m (" + num(cornell::kLightMin.y - kCircleCentre.y) +
          " m under the ceiling), a LINEAR key every frame: frame 0 at " + vec(on_circle(0)) +
          ", frame 15 at " + vec(on_circle(15)) +
          ". A STEP key of the parent node `light_rig` "
          "at t = " +
          num(kJumpTime, 6) +
          " s (half-way between frames 29 and 30) moves the "
          "light to " +
          vec(kJumpTarget) + " m, where it stays for frames 30-" + std::to_string(kFrames - 1) +
          ".",
      "Sequence: " + std::to_string(kFrames) + " frames at " + num(kFps) +
          " fps. The step change for lag is at frame t0 = " + std::to_string(kLoopFrames) + ".",
  };
  return s;
}

}  // namespace giq::scenegen
