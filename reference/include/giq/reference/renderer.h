#pragma once
// The reference path tracer: renders samples of a Scene seen through a Camera into a Film.
//
// Light transport: unidirectional path tracing with next-event estimation and multiple
// importance sampling (Veach 1997, thesis, chapter 9; power heuristic), Russian roulette
// after the third bounce, specialised at compile time on the scene's FeatureSet, and eight
// paths at a time where the scene's materials allow. See docs/reference.md for the units, the
// layers and what the tests prove.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "giq/reference/film.h"
#include "giq/scenes/camera.h"
#include "giq/scenes/scene.h"

namespace giq::reference {

// Which estimators light a vertex. Mis is the renderer; the other two exist so tests can
// show that all three converge to the same image.
enum class Estimator {
  Mis,        // light sampling and BSDF sampling, power heuristic
  LightOnly,  // area lights and the environment by light sampling only
  BsdfOnly,   // area lights and the environment by BSDF sampling only
};               // (punctual lights are always light-sampled: BSDF sampling cannot hit them)

// Where a path's random numbers come from (reference/sampling.h).
enum class Sampler {
  Sobol,        // Owen-scrambled Sobol nets in independent blocks: lower error per sample
  Independent,  // a hash per number: samples independent of each other
};

// "sobol" or "independent" (the command-line names); parse_sampler throws InputError naming
// `option` for anything else.
const char* sampler_name(Sampler s);
Sampler parse_sampler(const std::string& name, const std::string& option = "--sampler");

struct RenderSettings {
  int width = 256;
  int height = 256;
  uint64_t seed = 0;
  // Scattering events per path: 0 = emission seen directly, 1 = direct lighting, ... Russian
  // roulette ends most paths long before the default.
  int max_bounces = 64;
  Estimator estimator = Estimator::Mis;
  int threads = 0;  // 0 = all hardware threads; never changes the image
  // Run the integrator variant with every feature compiled in instead of the scene's own
  // (for benchmarks: the cost of not specialising). Never changes the image.
  bool all_features = false;
  // Eight paths at a time (reference/src/lane_integrator.h) or one at a time, always with the
  // same image. The lanes need the Sobol sampler. Auto takes them where they are faster:
  // Lambertian, untextured scenes (1.1x to 1.3x). On scenes with GGX lobes or textures they
  // measured 0.85x to 1.04x (docs/reference.md, "Light transport").
  enum class Lanes { Auto, Always, Never };
  Lanes lanes = Lanes::Auto;
  Sampler sampler = Sampler::Sobol;
  // Every camera ray through its pixel's centre instead of a uniformly distributed point of
  // the pixel (the box filter): the point a G-buffer shades, for comparing a technique's own
  // converged samples at pixel centres with the truth at the same points (tests). Edges alias.
  bool pixel_centre = false;
  // Samples per independently scrambled block of the Sobol sampler, a power of two from 2 to
  // 256. Larger blocks stratify more (on the Cornell box relMSE x spp is 0.135 with 16, 0.124
  // with 32, 0.111 with 64, 0.203 with independent samples); smaller ones give the variance
  // estimate more degrees of freedom (one per block: docs/reference.md, "Sampling").
  uint32_t sobol_block = 32;
  // Samples per block as the film counts them: 0 when samples are independent.
  uint32_t block() const { return sampler == Sampler::Sobol ? sobol_block : 0; }
};

// "sobol, blocks of 32" or "independent", for reports.
std::string describe_sampler(const RenderSettings& s);

struct RenderStats {
  uint64_t rays = 0;     // camera, bounce and shadow rays traced
  uint64_t samples = 0;  // camera paths
};

class Renderer {
 public:
  // camera: in the scene's local frame (Scene::views, or scenes::Camera::look_at). Throws
  // InputError for settings out of range.
  Renderer(const scenes::Scene& scene, const scenes::Camera& camera, const RenderSettings& settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const RenderSettings& settings() const;
  Film make_film() const;

  // Fills the first-hit layers (albedo, N, Z, objectId) from each pixel centre's ray; `only`
  // as in render().
  void render_aux(Film& film, const std::function<bool(int x0, int y0)>& only = {}) const;

  // Adds samples until every pixel has `target_spp`. Work is split in tiles; when `cancel`
  // becomes true, tiles not yet started are skipped (their pixels keep fewer samples; the
  // film stays valid and can be completed later). Returns false when cancelled. `only`, when
  // given, picks the pixels to render by the top-left corner of each 16 x 16 tile (a shard's
  // share: part.h); the others are left as they are.
  bool render(Film& film, uint32_t target_spp, const std::atomic<bool>* cancel = nullptr, RenderStats* stats = nullptr,
              const std::function<bool(int x0, int y0)>& only = {}) const;

  // Whether render() traces eight paths at a time (RenderSettings::lanes and a scene that
  // allows it).
  bool lanes() const;

  // The instantiation the integrator runs, as feature bits (1 specular, 2 textures,
  // 4 punctual lights, 8 emissive triangles, 16 environment).
  unsigned feature_mask() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace giq::reference
