// `gi1`: AMD's GI-1.0 (Boissé, Meunier, de Dinechin, Oliver, Bartels, Veselov, Eto and Harada
// 2022, "GI-1.0: A Fast Scalable Two-Level Radiance Caching Scheme for Real-Time Global
// Illumination", AMD technical report 22-10-9831). Two levels of radiance cache:
//   screen cache  8x8 hemispherical probes on the visible surfaces, one per 8x8 tile, carried
//                 from frame to frame along the motion vectors (gi1_reproject.comp), spawned
//                 on a jittered pixel of one tile in each upscale x upscale spawn tile per frame
//                 (gi1_spawn.comp), rays moved from tiles that have history to tiles that have
//                 none (gi1_patch.comp), each new probe's rays guided by the hemisphere rebuilt
//                 from the probes around it (gi1_reconstruct.comp), traced (gi1_trace.comp),
//                 blended with that history (gi1_blend.comp), filtered and projected to
//                 spherical harmonics (gi1_mask.comp, gi1_filter.comp), interpolated at every
//                 pixel (gi1_interpolate.comp) and denoised (gi1_denoise_*.comp); probes it
//                 evicts kept in a persistent side cache for later probes on their surface
//                 (gi1_side_*.comp);
//   world cache   outgoing radiance at the probe rays' hits, in a hash map of tiles of 8x8
//                 cells with mip levels (gi1_hash.glsl, gi1_cache_update.comp,
//                 gi1_cache_resolve.comp), unused tiles evicted (gi1_evict.comp); the light
//                 at the hits sampled through a light grid and reservoirs kept in world
//                 space (gi1_light_grid.comp, gi1_light_sample.glsl);
//   near field    screen-space horizon-based occlusion and light within a few probe spacings
//                 (gi1_near_field.comp), combined with the probes in the interpolation.
// docs/techniques/gi1.md maps the report's sections to this code and lists where it departs.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "giq/realtime/context.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "passes/deferred_gi.h"
#include "techniques/gi1/gi1_projection.h"
#include "techniques/gi1/gi1_shared.h"
#include "techniques/gi1/gi1_side_cache.h"

namespace giq::realtime {
namespace {

// The albedo at the probe rays' hits is capped here before it multiplies last frame's
// irradiance (the feedback): below 1, so that the loop converges (as `ddgi`'s).
constexpr float kAlbedoCap = 0.9f;
// Frames of denoiser history kept through a frame in which the scene changed.
constexpr float kChangeHistory = 4.0f;

// The radical inverse of i in `base` (Halton 1964).
double halton(uint32_t i, uint32_t base) {
  double f = 1.0, r = 0.0;
  for (; i > 0; i /= base) {
    f /= base;
    r += f * double(i % base);
  }
  return r;
}

class Gi1 : public IndirectLight {
 public:
  Gi1(const TechniqueCreateInfo& ci, DeferredGi& frame) : scene_gpu_(ci.scene_gpu) {
    const auto& p = ci.parameters;
    upscale_ = glm::uvec2(uint32_t(p.get_int("upscale")));
    world_cell_pixels_ = float(p.get("world_cell_pixels"));
    world_cell_min_ = float(p.get("world_cell_min")) * ci.scene.bounds.largest_side();
    buckets_ = 1u << p.get_int("cache_buckets_log2");
    tiles_per_bucket_ = 1u << p.get_int("cache_tiles_per_bucket_log2");
    cache_samples_ = uint32_t(p.get_int("cache_samples"));
    cache_decay_ = uint32_t(p.get_int("cache_decay"));
    seed_ = uint32_t(p.get_int("seed"));
    hysteresis_ = float(p.get_int("hysteresis"));
    denoise_history_ = float(p.get_int("denoise_history"));
    denoise_radius_ = float(p.get("denoise_radius"));
    filter_radius_ = uint32_t(p.get_int("probe_filter"));
    switches_ = (p.get_int("ray_length_bit") ? GIQ_GI1_RAY_LENGTH_BIT : 0u) |
                (p.get_int("adaptive_sampling") ? GIQ_GI1_ADAPTIVE_SAMPLING : 0u) |
                (p.get_int("feedback") ? GIQ_GI1_FEEDBACK : 0u) |
                (p.get_int("ray_guiding") ? GIQ_GI1_RAY_GUIDING : 0u) |
                (p.get_int("near_field") ? GIQ_GI1_NEAR_FIELD : 0u) |
                (p.get_int("side_cache") ? GIQ_GI1_SIDE_CACHE : 0u) |
                (p.get_int("light_sampling") ? GIQ_GI1_LIGHT_SAMPLING : 0u);
    light_candidates_ = uint32_t(p.get_int("light_candidates"));
    grid_cells_ = uint32_t(p.get_int("light_grid_cells"));
    grid_lights_ = uint32_t(p.get_int("light_grid_lights"));
    reuse_ = uint32_t(p.get_int("light_reuse"));
    near_ = glm::vec4(float(p.get("near_field_radius")), float(p.get_int("near_field_steps")), 0.0f, 0.0f);

    width_ = frame.width();
    height_ = frame.height();
    tiles_ = glm::uvec2((width_ + GIQ_GI1_PROBE - 1) / GIQ_GI1_PROBE,
                        (height_ + GIQ_GI1_PROBE - 1) / GIQ_GI1_PROBE);
    spawn_tiles_ = (tiles_ + upscale_ - 1u) / upscale_;
    const uint64_t tiles = uint64_t(tiles_.x) * tiles_.y,
                   slots = uint64_t(spawn_tiles_.x) * spawn_tiles_.y;
    cache_tiles_ = buckets_ * tiles_per_bucket_;

    const VkBufferUsageFlags storage =
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    auto buffer = [&](uint64_t bytes, VkBufferUsageFlags extra = 0) {
      return Buffer(ci.ctx, std::max<uint64_t>(bytes, 16), storage | extra);
    };
    frame_buffer_ = buffer(sizeof(gpu::GpuGi1Frame));
    for (int i = 0; i < 2; ++i) {
      probes_[i] = buffer(tiles * sizeof(gpu::GpuGi1Probe));
      radiance_[i] = buffer(tiles * GIQ_GI1_CELLS * 16);
      harmonics_[i] = buffer(tiles * GIQ_GI1_SH * 16);
      irradiance_[i] = Image(
          ci.ctx, {width_, height_, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
      history_length_[i] =
          Image(ci.ctx, {width_, height_, 1, VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
    }
    raw_ = Image(ci.ctx,
                 {width_, height_, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
    // The near field's images, a texel each where it is off (bound, never read).
    const bool near = (switches_ & GIQ_GI1_NEAR_FIELD) != 0u;
    const uint32_t near_w = near ? width_ : 1u, near_h = near ? height_ : 1u;
    near_field_ = Image(ci.ctx, {near_w, near_h, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
    bent_normal_ = Image(ci.ctx, {near_w, near_h, 1, VK_FORMAT_R16G16B16A16_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
    mask_levels_ = 1;
    uint64_t mask_entries = 0;
    for (glm::uvec2 m = tiles_;; m = (m + 1u) / 2u, ++mask_levels_) {
      mask_entries += uint64_t(m.x) * m.y;
      if (m.x == 1 && m.y == 1) break;
    }
    mask_ = buffer(mask_entries * 4);
    scratch_ = buffer(tiles * GIQ_GI1_CELLS * 16);
    spawn_ = buffer(tiles * 8);
    spawn_list_ = buffer(slots * 4);
    overrides_ = buffer(tiles * 4);
    empties_ = buffer(tiles * 4);
    counters_ = buffer(sizeof(gpu::GpuGi1Counters), VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    guide_ = buffer(slots * GIQ_GI1_CELLS * 16);
    ray_cells_ = buffer(slots * GIQ_GI1_CELLS * 8);
    fresh_ = buffer(slots * sizeof(gpu::GpuGi1Probe));
    queries_ = buffer(slots * GIQ_GI1_CELLS * sizeof(gpu::GpuGi1Query));
    cache_hash_ = buffer(uint64_t(cache_tiles_) * 4);
    cache_stamp_ = buffer(uint64_t(cache_tiles_) * 4);
    cache_cells_ = buffer(uint64_t(cache_tiles_) * GIQ_GI1_TILE_CELLS * 16);
    cache_max_ = buffer(uint64_t(cache_tiles_) * GIQ_GI1_CELLS * 4);
    cache_sums_ = buffer(uint64_t(cache_tiles_) * GIQ_GI1_CELLS * 16);
    touched_ = buffer(uint64_t(cache_tiles_) * 4);
    projection_ = Buffer::storage(ci.ctx, gi1_projection_table());
    probes_layer_ = &frame.add_layer("probes");
    // The light grid (at most light_grid_cells^3 cells, each a count and its lights) and the
    // reservoir grid (as many slots as the world cache has tiles), a word each where lights are
    // evaluated exactly (bound, never read).
    const bool sampling = (switches_ & GIQ_GI1_LIGHT_SAMPLING) != 0u;
    const uint64_t grid_words = uint64_t(grid_cells_) * grid_cells_ * grid_cells_ * (grid_lights_ + 1);
    light_grid_ = buffer(sampling ? grid_words * 4 : 4);
    reservoirs_ = buffer(sampling ? uint64_t(cache_tiles_) * sizeof(gpu::GpuGi1Reservoir) : 4);
    reservoir_claims_ = buffer(sampling ? uint64_t(cache_tiles_) * 4 : 4);
    reservoir_stash_ = buffer(sampling ? slots * GIQ_GI1_CELLS * sizeof(gpu::GpuGi1Reservoir) : 4);

    const auto s = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, img = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    const auto defines = feature_defines(ci.scene.features);
    auto with_common = [&](std::vector<VkDescriptorType> extra) {
      auto b = GBufferPass::receiver_bindings();
      b.insert(b.end(), 7, s);
      b.insert(b.end(), extra.begin(), extra.end());
      return b;
    };
    auto compile = [&](const char* name, std::vector<VkDescriptorType> bindings,
                       uint32_t push = 0) {
      return Pipeline::compute(ci.ctx,
                               ci.compiler.compile(std::string("techniques/gi1/") + name, defines),
                               bindings, push);
    };
    reproject_ = compile("gi1_reproject.comp", with_common({img, img}));
    spawn_pass_ = compile("gi1_spawn.comp", with_common({s}));
    patch_ = compile("gi1_patch.comp", {s, s, s, s, s, s, s});
    reconstruct_ = compile("gi1_reconstruct.comp", with_common({s, s, s, s, s, s, s, s, s, s, s}));
    // The side cache: as many entries as screen tiles (the report's texture the size of the
    // probe grid).
    side_ = std::make_unique<Gi1SideCache>(
        ci.ctx, [&](const char* name, std::vector<VkDescriptorType> b) { return compile(name, std::move(b)); },
        (switches_ & GIQ_GI1_SIDE_CACHE) ? uint32_t(tiles) : 0u, tiles, slots);
    auto receiver = [&](std::vector<VkDescriptorType> extra) {
      auto b = GBufferPass::receiver_bindings();
      b.insert(b.end(), extra.begin(), extra.end());
      return b;
    };
    light_grid_pass_ = compile("gi1_light_grid.comp", with_common({s, s, s, s, s, s}));
    trace_ = compile("gi1_trace.comp", receiver({s, s, s, s, s, s, s, s, s, s, s, img, s, s, s, s, s}));
    reservoir_store_ = compile("gi1_reservoir_store.comp", {s, s, s, s});
    update_ = compile("gi1_cache_update.comp", {s, s, s, s});
    args_ = compile("gi1_args.comp", {s});
    resolve_ = compile("gi1_cache_resolve.comp", {s, s, s, s, s, s});
    blend_ = compile("gi1_blend.comp", {s, s, s, s, s, s, s, s, s, s, s, s, s, s});
    mask_pass_ = compile("gi1_mask.comp", {s, s, s}, 4);
    filter_ = compile("gi1_filter.comp", {s, s, s, s, s, s, s, s, s}, 16);
    evict_ = compile("gi1_evict.comp", {s, s, s}, 16);
    near_pass_ = compile("gi1_near_field.comp", with_common({img, img, img, img}));
    interpolate_ = compile("gi1_interpolate.comp", with_common({img, img, s, img, img}));
    temporal_ = compile("gi1_denoise_temporal.comp", receiver({s, img, img, img, img, img, img}));
    spatial_ = compile("gi1_denoise_spatial.comp", receiver({s, img, img, img}));
  }

  void record(const FrameInput& in, DeferredGi& frame) override {
    VkCommandBuffer cmd = in.cmd;
    const int cur = in.frame & 1, prev = 1 - cur;
    if (in.frame == 0) {
      for (Buffer* b :
           {&cache_hash_, &cache_stamp_, &cache_cells_, &cache_max_, &cache_sums_, &probes_[0],
            &probes_[1], &radiance_[0], &radiance_[1], &harmonics_[0], &harmonics_[1], &reservoirs_, &reservoir_stash_})
        vkCmdFillBuffer(cmd, b->handle(), 0, VK_WHOLE_SIZE, 0);
      side_->clear(cmd);
      const float none[4] = {0.0f, 0.0f, 0.0f, -1.0f};
      for (Image& i : irradiance_) i.clear(cmd, none);
      const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      for (Image& i : history_length_) i.clear(cmd, zero);
    }
    for (Image* i : {&irradiance_[0], &irradiance_[1], &history_length_[0], &history_length_[1], &raw_,
                     &near_field_, &bent_normal_})
      i->transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    probes_layer_->transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    Image& target = frame.indirect_target();
    target.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    const gpu::GpuGi1Frame f = frame_constants(in, frame);
    vkCmdUpdateBuffer(cmd, frame_buffer_.handle(), 0, sizeof(f), &f);
    vkCmdFillBuffer(cmd, counters_.handle(), 0, VK_WHOLE_SIZE, 0);
    side_->begin_frame(cmd);
    vkCmdFillBuffer(cmd, reservoir_claims_.handle(), 0, VK_WHOLE_SIZE, 0xffffffffu);
    full_barrier(cmd);

    auto common = [&] {
      auto d = frame.gbuffer().receiver_descriptors();
      d.insert(d.end(), {Descriptor::storage(frame_buffer_), Descriptor::storage(probes_[cur]),
                         Descriptor::storage(probes_[prev]), Descriptor::storage(radiance_[cur]),
                         Descriptor::storage(radiance_[prev]), Descriptor::storage(harmonics_[cur]),
                         Descriptor::storage(harmonics_[prev])});
      return d;
    };
    const uint32_t tiles = tiles_.x * tiles_.y;

    in.timer.begin(cmd, "gi1_reproject");
    reproject_.bind(cmd);
    auto d = common();
    d.insert(d.end(), {Descriptor::storage_image(frame.gbuffer().motion()),
                       Descriptor::storage_image(irradiance_[prev])});
    reproject_.push_descriptors(cmd, d);
    vkCmdDispatch(cmd, tiles_.x, tiles_.y, 1);
    full_barrier(cmd);
    in.timer.end(cmd);

    side_->bin(cmd, in.timer, frame_buffer_);

    in.timer.begin(cmd, "gi1_spawn");
    spawn_pass_.bind(cmd);
    d = common();
    d.push_back(Descriptor::storage(spawn_));
    spawn_pass_.push_descriptors(cmd, d);
    vkCmdDispatch(cmd, (tiles + 63) / 64, 1, 1);
    full_barrier(cmd);
    patch_.bind(cmd);
    patch_.push_descriptors(cmd, {Descriptor::storage(frame_buffer_),
                                  Descriptor::storage(probes_[cur]), Descriptor::storage(spawn_),
                                  Descriptor::storage(counters_), Descriptor::storage(spawn_list_),
                                  Descriptor::storage(overrides_), Descriptor::storage(empties_)});
    vkCmdDispatch(cmd, 1, 1, 1);
    full_barrier(cmd);
    in.timer.end(cmd);

    in.timer.begin(cmd, "gi1_reconstruct");
    reconstruct_.bind(cmd);
    d = common();
    d.insert(d.end(), {Descriptor::storage(spawn_), Descriptor::storage(spawn_list_),
                       Descriptor::storage(counters_), Descriptor::storage(guide_),
                       Descriptor::storage(ray_cells_), Descriptor::storage(fresh_)});
    for (const Descriptor& x : side_->reconstruct_descriptors(in.frame)) d.push_back(x);
    reconstruct_.push_descriptors(cmd, d);
    vkCmdDispatchIndirect(cmd, counters_.handle(), 0);
    full_barrier(cmd);
    in.timer.end(cmd);

    if (switches_ & GIQ_GI1_LIGHT_SAMPLING) {
      in.timer.begin(cmd, "gi1_light_grid");
      light_grid_pass_.bind(cmd);
      d = common();
      d.insert(d.end(), {Descriptor::storage(frame.direct_light().area_light_buffer()),
                         Descriptor::storage(frame.direct_light().area_triangle_buffer()),
                         Descriptor::storage(light_grid_)});
      for (const Descriptor& x : frame.direct_light().particle_tree_descriptors()) d.push_back(x);
      light_grid_pass_.push_descriptors(cmd, d);
      vkCmdDispatch(cmd, f.grid_cells.x * f.grid_cells.y, f.grid_cells.z, 1);  // a workgroup a cell
      full_barrier(cmd);
      in.timer.end(cmd);
    }

    in.timer.begin(cmd, "gi1_trace");
    trace_.bind(cmd);
    d = frame.gbuffer().receiver_descriptors();
    d.insert(d.end(),
             {Descriptor::storage(frame_buffer_), Descriptor::storage(spawn_), Descriptor::storage(spawn_list_),
              Descriptor::storage(counters_), Descriptor::storage(queries_),
              Descriptor::storage(cache_hash_), Descriptor::storage(cache_stamp_),
              Descriptor::storage(cache_max_), Descriptor::storage(touched_),
              Descriptor::storage(frame.direct_light().area_light_buffer()),
              Descriptor::storage(frame.direct_light().area_triangle_buffer()),
              Descriptor::storage_image(irradiance_[prev]), Descriptor::storage(ray_cells_),
              Descriptor::storage(light_grid_), Descriptor::storage(reservoirs_),
              Descriptor::storage(reservoir_claims_), Descriptor::storage(reservoir_stash_)});
    trace_.push_descriptors(cmd, d);
    vkCmdDispatchIndirect(cmd, counters_.handle(), 0);
    full_barrier(cmd);
    if (switches_ & GIQ_GI1_LIGHT_SAMPLING) {
      reservoir_store_.bind(cmd);
      reservoir_store_.push_descriptors(cmd, {Descriptor::storage(counters_), Descriptor::storage(reservoir_stash_),
                                              Descriptor::storage(reservoir_claims_), Descriptor::storage(reservoirs_)});
      vkCmdDispatchIndirect(cmd, counters_.handle(), 0);
      full_barrier(cmd);
    }
    in.timer.end(cmd);

    in.timer.begin(cmd, "gi1_cache");
    update_.bind(cmd);
    update_.push_descriptors(cmd,
                             {Descriptor::storage(counters_), Descriptor::storage(queries_),
                              Descriptor::storage(cache_max_), Descriptor::storage(cache_sums_)});
    vkCmdDispatchIndirect(cmd, counters_.handle(), 0);
    args_.bind(cmd);
    args_.push_descriptors(cmd, {Descriptor::storage(counters_)});
    vkCmdDispatch(cmd, 1, 1, 1);
    full_barrier(cmd);
    resolve_.bind(cmd);
    resolve_.push_descriptors(
        cmd, {Descriptor::storage(frame_buffer_), Descriptor::storage(counters_),
              Descriptor::storage(touched_), Descriptor::storage(cache_max_),
              Descriptor::storage(cache_sums_), Descriptor::storage(cache_cells_)});
    vkCmdDispatchIndirect(cmd, counters_.handle(), offsetof(gpu::GpuGi1Counters, tile_groups));
    full_barrier(cmd);
    in.timer.end(cmd);

    in.timer.begin(cmd, "gi1_blend");
    blend_.bind(cmd);
    d = {Descriptor::storage(frame_buffer_), Descriptor::storage(counters_),
         Descriptor::storage(spawn_list_),   Descriptor::storage(probes_[cur]),
         Descriptor::storage(queries_),      Descriptor::storage(cache_cells_),
         Descriptor::storage(radiance_[cur]), Descriptor::storage(guide_),
         Descriptor::storage(ray_cells_),    Descriptor::storage(fresh_)};
    for (const Descriptor& x : side_->blend_descriptors()) d.push_back(x);
    blend_.push_descriptors(cmd, d);
    vkCmdDispatchIndirect(cmd, counters_.handle(), 0);
    full_barrier(cmd);
    in.timer.end(cmd);

    side_->reorder(cmd, in.timer, frame_buffer_, in.frame);

    in.timer.begin(cmd, "gi1_filter");
    mask_pass_.bind(cmd);
    mask_pass_.push_descriptors(
        cmd, {Descriptor::storage(frame_buffer_), Descriptor::storage(probes_[cur]),
              Descriptor::storage(mask_)});
    glm::uvec2 level_size = tiles_;
    for (uint32_t level = 0; level < mask_levels_; ++level, level_size = (level_size + 1u) / 2u) {
      mask_pass_.push_constants(cmd, level);
      mask_pass_.dispatch_2d(cmd, level_size.x, level_size.y);
      compute_barrier(cmd);
    }
    filter_.bind(cmd);
    filter_.push_descriptors(cmd,
                             {Descriptor::storage(frame_buffer_), Descriptor::storage(counters_),
                              Descriptor::storage(spawn_list_), Descriptor::storage(probes_[cur]),
                              Descriptor::storage(mask_), Descriptor::storage(radiance_[cur]),
                              Descriptor::storage(scratch_), Descriptor::storage(harmonics_[cur]),
                              Descriptor::storage(projection_)});
    for (uint32_t second = 0; second < 2; ++second) {
      struct {
        glm::ivec2 direction;
        uint32_t second, radius;
      } fp{second ? glm::ivec2(0, 1) : glm::ivec2(1, 0), second, filter_radius_};
      filter_.push_constants(cmd, fp);
      vkCmdDispatchIndirect(cmd, counters_.handle(), 0);
      full_barrier(cmd);
    }
    in.timer.end(cmd);

    if (switches_ & GIQ_GI1_NEAR_FIELD) {
      in.timer.begin(cmd, "gi1_near_field");
      near_pass_.bind(cmd);
      d = common();
      d.insert(d.end(), {Descriptor::storage_image(frame.direct_light().output()),
                         Descriptor::storage_image(irradiance_[prev]), Descriptor::storage_image(near_field_),
                         Descriptor::storage_image(bent_normal_)});
      near_pass_.push_descriptors(cmd, d);
      near_pass_.dispatch_2d(cmd, width_, height_);
      full_barrier(cmd);
      in.timer.end(cmd);
    }

    in.timer.begin(cmd, "gi1_interpolate");
    interpolate_.bind(cmd);
    d = common();
    d.insert(d.end(), {Descriptor::storage_image(raw_), Descriptor::storage_image(*probes_layer_),
                       Descriptor::storage(mask_), Descriptor::storage_image(near_field_),
                       Descriptor::storage_image(bent_normal_)});
    interpolate_.push_descriptors(cmd, d);
    interpolate_.dispatch_2d(cmd, width_, height_);
    full_barrier(cmd);
    in.timer.end(cmd);

    in.timer.begin(cmd, "gi1_denoise");
    temporal_.bind(cmd);
    d = frame.gbuffer().receiver_descriptors();
    d.insert(
        d.end(),
        {Descriptor::storage(frame_buffer_), Descriptor::storage_image(frame.gbuffer().motion()),
         Descriptor::storage_image(raw_), Descriptor::storage_image(irradiance_[prev]),
         Descriptor::storage_image(history_length_[prev]),
         Descriptor::storage_image(irradiance_[cur]),
         Descriptor::storage_image(history_length_[cur])});
    temporal_.push_descriptors(cmd, d);
    temporal_.dispatch_2d(cmd, width_, height_);
    full_barrier(cmd);
    spatial_.bind(cmd);
    d = frame.gbuffer().receiver_descriptors();
    d.insert(d.end(),
             {Descriptor::storage(frame_buffer_), Descriptor::storage_image(irradiance_[cur]),
              Descriptor::storage_image(history_length_[cur]), Descriptor::storage_image(target)});
    spatial_.push_descriptors(cmd, d);
    spatial_.dispatch_2d(cmd, width_, height_);
    full_barrier(cmd);
    in.timer.end(cmd);

    // After the frame's lookups: tiles unused for `decay` frames leave the cache.
    in.timer.begin(cmd, "gi1_evict");
    struct {
      uint32_t tiles, frame, decay;
      float react;
    } ep{cache_tiles_, uint32_t(in.frame), cache_decay_,
         in.change == SceneChange::None ? 0.0f : std::max(1.0f, float(cache_samples_) / 4.0f)};
    evict_.bind(cmd);
    evict_.push_descriptors(cmd,
                            {Descriptor::storage(cache_hash_), Descriptor::storage(cache_stamp_),
                             Descriptor::storage(cache_cells_)});
    evict_.push_constants(cmd, ep);
    vkCmdDispatch(cmd, (cache_tiles_ + 63) / 64, 1, 1);
    full_barrier(cmd);
    in.timer.end(cmd);
    previous_camera_ = in.camera;
  }

 private:
  gpu::GpuGi1Frame frame_constants(const FrameInput& in, DeferredGi& frame) const {
    gpu::GpuGi1Frame f{};
    f.camera = gpu::make_gpu_camera(in.camera);
    f.previous = gpu::make_gpu_camera(in.frame > 0 ? previous_camera_ : in.camera);
    f.environment = glm::vec4(in.scene.environment, float(in.scene.environment_map));
    f.size = glm::uvec4(width_, height_, tiles_);
    f.spawn = glm::uvec4(upscale_, spawn_tiles_);
    // This frame's pixel in each tile (Halton's bases 2 and 3), and the tile of each spawn
    // tile that spawns: the n tiles in the order k -> 7k + 3 mod n, so that every tile
    // spawns once in n frames (7 is prime to every n = upscale_x * upscale_y <= 16).
    const uint32_t i = uint32_t(in.frame) + 1u, n = upscale_.x * upscale_.y;
    const glm::uvec2 pixel(uint32_t(halton(i, 2) * GIQ_GI1_PROBE),
                           uint32_t(halton(i, 3) * GIQ_GI1_PROBE));
    const uint32_t k = (uint32_t(in.frame) % n * 7u + 3u) % n;
    f.jitter = glm::uvec4(pixel.x | pixel.y << 16, (k % upscale_.x) | (k / upscale_.x) << 16,
                          uint32_t(in.frame), seed_);
    f.counts = glm::uvec4(
        scene_gpu_.light_count(), uint32_t(frame.direct_light().area_lights().size()),
        spawn_tiles_.x * spawn_tiles_.y, switches_ | (in.frame > 0 ? GIQ_GI1_HISTORY : 0u));
    f.cache = glm::uvec4(buckets_, tiles_per_bucket_, cache_decay_, cache_samples_);
    // A pixel's side: 2 tan(yfov / 2) / height per unit of view depth, or 2 ymag / height.
    const float h = float(height_);
    f.pixel = in.camera.orthographic()
                  ? glm::vec4(0.0f, 2.0f * in.camera.ymag / h, world_cell_pixels_, world_cell_min_)
                  : glm::vec4(2.0f * std::tan(0.5f * in.camera.yfov) / h, 0.0f, world_cell_pixels_,
                              world_cell_min_);
    // When lights or geometry moved, the denoiser keeps at most kChangeHistory frames of
    // history this frame (and the world cache's cells a quarter of their samples, gi1_evict),
    // so that old light fades within a few frames instead of `denoise_history`.
    const float history = in.change == SceneChange::None ? denoise_history_
                                                         : std::min(denoise_history_, kChangeHistory);
    f.params = glm::vec4(kAlbedoCap, hysteresis_, history, denoise_radius_);
    f.mask = glm::uvec4(mask_levels_, 0u, 0u, 0u);
    f.near = near_;
    f.side = glm::uvec4(side_->entries(), uint32_t(in.frame) + 1u, 0u, 0u);
    // The light grid: cubic cells over the scene's bounds, light_grid_cells along the longest
    // side (gi1_light_grid.comp).
    const scenes::Bounds& b = in.scene.bounds;
    const float cell = b.largest_side() / float(grid_cells_);
    const glm::uvec3 cells = glm::clamp(glm::uvec3(glm::ceil(b.extent() / cell)), glm::uvec3(1u), glm::uvec3(grid_cells_));
    f.grid = glm::vec4(b.empty() ? glm::vec3(0.0f) : b.lo, cell);
    f.grid_cells = glm::uvec4(cells, grid_lights_);
    const bool environment = in.scene.environment != glm::vec3(0.0f) || in.scene.environment_map >= 0;
    // Reservoirs carry over only while nothing moved: a stored point on an emitter that moved
    // is not on it any more.
    const bool reuse = reuse_ > 0 && in.frame > 0 && in.change == SceneChange::None;
    f.lights = glm::uvec4(f.counts.x + f.counts.y + (environment ? 1u : 0u), light_candidates_,
                          reuse ? reuse_ * light_candidates_ : 0u, cache_tiles_);
    return f;
  }

  const SceneGpu& scene_gpu_;
  glm::uvec2 upscale_{2}, tiles_{0}, spawn_tiles_{0};
  uint32_t width_ = 0, height_ = 0;
  float world_cell_pixels_ = 32.0f, world_cell_min_ = 0.0f;
  uint32_t buckets_ = 4096, tiles_per_bucket_ = 16, cache_tiles_ = 0, cache_samples_ = 16,
           cache_decay_ = 50;
  uint32_t seed_ = 0, switches_ = 0, filter_radius_ = 3, mask_levels_ = 1;
  uint32_t light_candidates_ = 8, grid_cells_ = 16, grid_lights_ = 32, reuse_ = 8;
  float hysteresis_ = 1.0f, denoise_history_ = 16.0f, denoise_radius_ = 8.0f;
  glm::vec4 near_{0.0f};
  scenes::Camera previous_camera_;
  Buffer frame_buffer_, guide_, ray_cells_, fresh_, probes_[2], radiance_[2], harmonics_[2], mask_,
      scratch_, spawn_, spawn_list_, overrides_, empties_, counters_, queries_, cache_hash_,
      cache_stamp_, cache_cells_, cache_max_, cache_sums_, touched_, projection_, light_grid_, reservoirs_,
      reservoir_claims_, reservoir_stash_;
  Image irradiance_[2], history_length_[2], raw_, near_field_, bent_normal_;
  Image* probes_layer_ = nullptr;
  Pipeline reproject_, spawn_pass_, patch_, reconstruct_, trace_, update_, args_, resolve_, blend_,
      mask_pass_, filter_, evict_, near_pass_, interpolate_, temporal_, spatial_, light_grid_pass_,
      reservoir_store_;
  std::unique_ptr<Gi1SideCache> side_;
};

}  // namespace

TechniqueInfo gi1_technique() {
  FrameNeeds needs;
  needs.motion_vectors = true;
  TechniqueInfo info = deferred_technique<Gi1>(
      "gi1",
      "GI-1.0 (Boisse et al. 2022): screen probes on the visible surfaces, spawned on "
      "1/upscale^2 of the tiles a frame and carried along the motion vectors, their rays guided "
      "by the hemisphere rebuilt from the probes around them and their hits cached in a "
      "world-space hash grid of tiles with mip levels; 7x7 probe filter, spherical-harmonic "
      "interpolation per pixel, denoiser",
      needs,
      {{"upscale", 2, 1, 4, true,
        "temporal upscale per axis: one tile of each upscale x upscale spawn tile gets a new probe "
        "each frame "
        "(2: 1/4 ray per pixel)"},
       {"world_cell_pixels", 32, 2, 512, false,
        "a world-cache cell's size in pixels at its distance from the camera (rounded down to a "
        "power of two)"},
       {"world_cell_min", 0.01, 0, 1, false,
        "the smallest world-cache cell, as a fraction of the scene's largest side"},
       {"cache_buckets_log2", 12, 4, 16, true,
        "log2 of the world cache's buckets (hash map slots of tiles)"},
       {"cache_tiles_per_bucket_log2", 4, 0, 5, true,
        "log2 of the tiles (8x8 cells and their mips) per bucket"},
       {"cache_samples", 16, 1, 1024, true,
        "samples a world-cache cell averages (its moving average's cap)"},
       {"cache_decay", 50, 1, 100000, true, "frames a world-cache tile no ray reaches lives"},
       {"ray_length_bit", 1, 0, 1, true,
        "1: a ray shorter than a world-cache tile files its hit under another key (section 2.2.2; "
        "stops leaks "
        "through thin walls)"},
       {"ray_guiding", 1, 0, 1, true,
        "1: a new probe's 64 rays pick cells by the luminance reconstructed from last frame's "
        "probes "
        "around it (section 2.1.3); 0: one ray per cell"},
       {"hysteresis", 1, 0, 1, true,
        "1: a probe blends new radiance with its history by the shadow-preserving hysteresis "
        "(section 2.1.4, "
        "Algorithm 3; biased dark); 0: new radiance replaces it"},
       {"probe_filter", 3, 0, 3, true,
        "probes filtered across this many neighbours on each side per axis (section 2.1.6; 3: 7x7; "
        "0: off)"},
       {"adaptive_sampling", 1, 0, 1, true,
        "1: rays move from tiles with history to tiles without (section 2.1.2, Algorithm 2)"},
       {"denoise_history", 16, 0, 1024, true,
        "frames the denoiser's temporal accumulation averages at most (section 2.4.3; 0: off)"},
       {"denoise_radius", 8, 0, 64, false,
        "the denoiser's spatial blur radius in pixels for a pixel without history, divided by the "
        "history's length (0: off)"},
       {"feedback", 1, 0, 1, true,
        "1: hits on screen add last frame's indirect irradiance there (multi-bounce, section "
        "2.2.4)"},
       {"light_sampling", 1, 0, 1, true,
        "1: the lights at the probe rays' hits are sampled, the environment among them: candidates from "
        "the light grid resampled into a reservoir, one shadow ray (section 2.3); 0: every light "
        "evaluated exactly, one shadow ray each, the environment left out"},
       {"light_candidates", 8, 1, 64, true, "candidates resampled per hit (section 2.3.1)"},
       {"light_reuse", 8, 0, 64, true,
        "frames of candidates a hit's reservoir may carry into the next frame's in its cell of the "
        "reservoir grid (section 2.3.1, world-space temporal reuse; 0: none)"},
       {"light_grid_cells", 16, 1, 64, true, "the light grid's cells along the scene's longest side"},
       {"light_grid_lights", 32, 1, 64, true, "the lights a light-grid cell lists at most, the most important"},
       {"side_cache", 1, 0, 1, true,
        "1: probes the screen cache evicts are kept in a persistent LRU side cache and reused by later "
        "probes on their surface (section 2.1.8; thin geometry)"},
       {"near_field", 1, 0, 1, true,
        "1: the screen-space near field (section 3): horizon-based occlusion and light of the surfaces "
        "within near_field_radius pixels, where the probes are too sparse"},
       {"near_field_radius", 16, 2, 128, false, "the near field's reach in pixels (probes are 8 apart)"},
       {"near_field_steps", 8, 1, 64, true, "the near field's samples on each side of its slice"},
       {"seed", 0, 0, 2147483647, true, "random sequence; same seed, same image"}},
      {"upscale", {4, 3, 2, 1}});
  info.lights_with_environment = true;  // probe rays that miss see it
  return info;
}

}  // namespace giq::realtime
