#include "giq/reference/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <array>
#include <bit>
#include <cmath>
#include <string>
#include <utility>

#include "giq/base/error.h"
#include "giq/reference/part.h"
#include "lane_integrator.h"
#include "path_integrator.h"

namespace giq::reference {
namespace {

constexpr int kTile = 16;

// The work of one tile, instantiated per feature mask: render() picks the instantiation once
// and every pixel of every pass runs the specialised code.
struct Kernels {
  RenderStats (*render_tile)(const RenderContext&, Film&, int x0, int y0, uint32_t target_spp);
  PixelAux (*aux)(const RenderContext&, int x, int y);
};

template <unsigned F>
RenderStats render_tile(const RenderContext& ctx, Film& film, int x0, int y0, uint32_t target_spp) {
  const int x1 = std::min(x0 + kTile, film.width), y1 = std::min(y0 + kTile, film.height);
  if (lanes_support(F, ctx.settings)) return LaneIntegrator<F>(ctx).render_tile(film, x0, y0, x1, y1, target_spp);
  const PathIntegrator<F> integrator(ctx);
  RenderStats stats;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      PixelAccumulator& acc = film.pixels[size_t(y) * size_t(film.width) + size_t(x)];
      while (acc.samples < target_spp) {
        const PathResult r = integrator.trace(x, y, acc.samples);
        stats.rays += r.rays;
        ++stats.samples;
        add_sample(acc, r.direct, r.indirect);
      }
    }
  }
  return stats;
}

template <unsigned F>
constexpr Kernels kernels_for() {
  return {&render_tile<F>, [](const RenderContext& c, int x, int y) { return PathIntegrator<F>(c).aux(x, y); }};
}

template <size_t... I>
constexpr std::array<Kernels, sizeof...(I)> make_kernel_table(std::index_sequence<I...>) {
  return {kernels_for<unsigned(I)>()...};
}

constexpr auto kKernels = make_kernel_table(std::make_index_sequence<(1u << kFeatureCount)>{});

void validate(const RenderSettings& s) {
  if (s.width < 1 || s.width > 65536) throw InputError("", "--width", "width " + std::to_string(s.width) + " is out of range; expected 1 to 65536");
  if (s.height < 1 || s.height > 65536)
    throw InputError("", "--height", "height " + std::to_string(s.height) + " is out of range; expected 1 to 65536");
  if (s.max_bounces < 0 || s.max_bounces > 100000)
    throw InputError("", "--max-bounces", "max bounces " + std::to_string(s.max_bounces) + " is out of range; expected 0 to 100000");
  if (s.sampler == Sampler::Sobol && (s.sobol_block < 2 || s.sobol_block > (1u << kSobolMaxBits) || !std::has_single_bit(s.sobol_block)))
    throw InputError("", "--sobol-block", "block " + std::to_string(s.sobol_block) + " is not a power of two from 2 to 256");
  if (s.threads < 0) throw InputError("", "--threads", "threads " + std::to_string(s.threads) + " must be >= 0 (0 = all cores)");
}

}  // namespace

struct Renderer::Impl {
  Impl(const scenes::Scene& scene, const scenes::Camera& camera, const RenderSettings& settings)
      : ctx(scene, camera, settings, scene.bounds.centre(), std::max(1e-30f, 0.5f * glm::length(scene.bounds.extent()))),
        mask(settings.all_features ? (1u << kFeatureCount) - 1 : reference::feature_mask(scene.features)),
        kernels(kKernels[mask]) {}
  RenderContext ctx;
  unsigned mask;
  Kernels kernels;

  template <class Fn>
  void run(Fn&& fn) const {
    if (ctx.settings.threads > 0) {
      tbb::task_arena arena(ctx.settings.threads);
      arena.execute(fn);
    } else {
      fn();
    }
  }
};

const char* sampler_name(Sampler s) { return s == Sampler::Sobol ? "sobol" : "independent"; }

std::string describe_sampler(const RenderSettings& s) {
  return s.block() ? "sobol, blocks of " + std::to_string(s.block()) : std::string("independent");
}

Sampler parse_sampler(const std::string& name, const std::string& option) {
  if (name == "sobol") return Sampler::Sobol;
  if (name == "independent") return Sampler::Independent;
  throw InputError("", option, "'" + name + "' is not one of sobol, independent");
}

Renderer::Renderer(const scenes::Scene& scene, const scenes::Camera& camera, const RenderSettings& settings) {
  validate(settings);
  impl_ = std::make_unique<Impl>(scene, camera, settings);
}

Renderer::~Renderer() = default;

const RenderSettings& Renderer::settings() const { return impl_->ctx.settings; }
unsigned Renderer::feature_mask() const { return impl_->mask; }
bool Renderer::lanes() const { return lanes_support(impl_->mask, impl_->ctx.settings); }
Film Renderer::make_film() const {
  const RenderSettings& s = impl_->ctx.settings;
  return Film(s.width, s.height, s.block());
}

void Renderer::render_aux(Film& film, const std::function<bool(int x0, int y0)>& only) const {
  const RenderContext& ctx = impl_->ctx;
  const int tiles_x = (film.width + kTile - 1) / kTile, tiles_y = (film.height + kTile - 1) / kTile;
  impl_->run([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y), [&](const tbb::blocked_range<int>& r) {
      for (int t = r.begin(); t < r.end(); ++t) {
        const int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
        if (only && !only(x0, y0)) continue;
        for (int y = y0; y < std::min(y0 + kTile, film.height); ++y)
          for (int x = x0; x < std::min(x0 + kTile, film.width); ++x)
            film.aux[size_t(y) * size_t(film.width) + size_t(x)] = impl_->kernels.aux(ctx, x, y);
      }
    });
  });
}

// A shard's units (part.h) are whole tiles.
static_assert(kUnitSize % kTile == 0);

bool Renderer::render(Film& film, uint32_t target_spp, const std::atomic<bool>* cancel, RenderStats* stats,
                      const std::function<bool(int x0, int y0)>& only) const {
  const RenderContext& ctx = impl_->ctx;
  const int tiles_x = (film.width + kTile - 1) / kTile, tiles_y = (film.height + kTile - 1) / kTile;
  std::atomic<bool> skipped{false};
  std::atomic<uint64_t> rays{0}, samples{0};
  impl_->run([&] {
    // Pixels are independent and each accumulates its samples in index order, so the
    // schedule cannot change a bit of the result.
    tbb::parallel_for(
        tbb::blocked_range<int>(0, tiles_x * tiles_y, 1),
        [&](const tbb::blocked_range<int>& r) {
          for (int t = r.begin(); t < r.end(); ++t) {
            if (cancel != nullptr && cancel->load(std::memory_order_relaxed)) {
              skipped = true;
              continue;
            }
            const int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
            if (only && !only(x0, y0)) continue;
            const RenderStats s = impl_->kernels.render_tile(ctx, film, x0, y0, target_spp);
            rays.fetch_add(s.rays, std::memory_order_relaxed);
            samples.fetch_add(s.samples, std::memory_order_relaxed);
          }
        },
        tbb::simple_partitioner());
  });
  if (stats != nullptr) stats->rays += rays, stats->samples += samples;
  return !skipped;
}

}  // namespace giq::reference
