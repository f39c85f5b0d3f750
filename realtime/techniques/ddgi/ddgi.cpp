// `ddgi`: Dynamic Diffuse Global Illumination (Majercik, Guertin, Nowrouzezahrai and McGuire
// 2019, "Dynamic Diffuse Global Illumination with Ray-Traced Irradiance Fields", JCGT 8(2);
// probe relocation and classification: Majercik, Marrs, Spjut and McGuire 2021, "Scaling
// Probe-Based Real-Time Dynamic Global Illumination for Production", JCGT 10(2)). A grid of
// probes fitted to the scene's bounds; every frame each probe traces rays through the shared
// compute BVH (ddgi_trace.comp), blends their radiance into an octahedral irradiance map and
// their hit distances into a map of distance moments (ddgi_blend.comp, ddgi_border.comp),
// moves out of walls and switches itself off where it cannot help (ddgi_probes.comp); every
// pixel then reads the 8 probes around it with Chebyshev visibility (ddgi_shade.comp).
// docs/techniques/ddgi.md maps the papers' equations to this code.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "giq/base/error.h"
#include "giq/realtime/context.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "passes/deferred_gi.h"
#include "techniques/ddgi/ddgi_shared.h"

namespace giq::realtime {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr uint32_t kMaxGroups = 65535;  // the minimum maxComputeWorkGroupCount per axis

// The papers' thresholds (RTXGI's defaults), here relative to a texel's encoded value.
constexpr float kChangeThreshold = 0.2f;
constexpr float kBrightnessThreshold = 0.1f;
// A probe whose fixed rays hit back faces more often than this is inside geometry (RTXGI's
// default backface threshold).
constexpr float kBackfaceThreshold = 0.25f;
// The diffuse albedo at probe-ray hits is capped here before it multiplies the volume's own
// irradiance: below 1, as the papers require, so that the feedback loop converges.
constexpr float kAlbedoCap = 0.9f;

// Bytes one probe needs: its two tiles, its rays, its data and history.
uint64_t probe_bytes(uint32_t irradiance_texels, uint32_t distance_texels, uint32_t rays) {
  const uint64_t ni = irradiance_texels + 2, nd = distance_texels + 2;
  return ni * ni * 16 + nd * nd * 8 + uint64_t(rays) * 16 + sizeof(gpu::GpuDdgiProbe) + 4;
}

// A uniformly distributed random rotation (Shoemake 1992, "Uniform Random Rotations",
// Graphics Gems III), the same for a given frame in every run; as rows of a matrix.
void random_rotation(int frame, glm::vec4 rows[3]) {
  uint64_t state = 0x9e3779b97f4a7c15ull * uint64_t(frame + 1);
  auto next = [&state] {  // splitmix64
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  const double u1 = next(), u2 = next(), u3 = next();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double x = a * std::sin(2 * kPi * u2), y = a * std::cos(2 * kPi * u2);
  const double z = b * std::sin(2 * kPi * u3), w = b * std::cos(2 * kPi * u3);
  rows[0] = glm::vec4(float(1 - 2 * (y * y + z * z)), float(2 * (x * y - z * w)), float(2 * (x * z + y * w)), 0.0f);
  rows[1] = glm::vec4(float(2 * (x * y + z * w)), float(1 - 2 * (x * x + z * z)), float(2 * (y * z - x * w)), 0.0f);
  rows[2] = glm::vec4(float(2 * (x * z - y * w)), float(2 * (y * z + x * w)), float(1 - 2 * (x * x + y * y)), 0.0f);
}

void require_linear_filter(Context& ctx, VkFormat format, const char* what) {
  VkFormatProperties props{};
  vkGetPhysicalDeviceFormatProperties(ctx.physical_device(), format, &props);
  const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT |
                                    VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT;
  if ((props.optimalTilingFeatures & need) != need)
    throw InputError("", "--technique", std::string("ddgi needs ") + what +
                                            " images that are both storage and linearly filtered; " +
                                            ctx.info().name + " cannot");
}

class Ddgi : public IndirectLight {
 public:
  Ddgi(const TechniqueCreateInfo& ci, DeferredGi& /*frame*/) : scene_gpu_(ci.scene_gpu) {
    const auto& p = ci.parameters;
    rays_ = uint32_t(p.get_int("rays_per_probe"));
    irradiance_texels_ = uint32_t(p.get_int("irradiance_texels"));
    distance_texels_ = uint32_t(p.get_int("distance_texels"));
    hysteresis_ = float(p.get("hysteresis"));
    feedback_ = p.get_int("feedback") != 0;
    fit_volume(ci, p);

    require_linear_filter(ci.ctx, VK_FORMAT_R32G32B32A32_SFLOAT, "RGBA32F");
    require_linear_filter(ci.ctx, VK_FORMAT_R32G32_SFLOAT, "RG32F");
    const uint32_t probes = volume_.counts.w, per_row = volume_.tiles.x;
    const uint32_t rows = (probes + per_row - 1) / per_row;
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    irradiance_ = Image(ci.ctx, {per_row * (irradiance_texels_ + 2), rows * (irradiance_texels_ + 2), 1,
                                 VK_FORMAT_R32G32B32A32_SFLOAT, usage});
    distance_ = Image(ci.ctx, {per_row * (distance_texels_ + 2), rows * (distance_texels_ + 2), 1,
                               VK_FORMAT_R32G32_SFLOAT, usage});
    volume_.atlas = glm::vec4(1.0f / float(irradiance_.desc().width), 1.0f / float(irradiance_.desc().height),
                              1.0f / float(distance_.desc().width), 1.0f / float(distance_.desc().height));
    volume_buffer_ = Buffer::storage(ci.ctx, &volume_, sizeof(volume_));
    probe_buffer_ = Buffer(ci.ctx, uint64_t(probes) * sizeof(gpu::GpuDdgiProbe),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    history_buffer_ = Buffer(ci.ctx, std::max<uint64_t>(16, uint64_t(probes) * 4),
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    ray_buffer_ = Buffer(ci.ctx, uint64_t(probes) * rays_ * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    sampler_ = Sampler(ci.ctx, true, false);

    const auto s = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, img = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
               smp = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    const auto defines = feature_defines(ci.scene.features);
    auto b = SceneGpu::binding_types();
    b.insert(b.end(), {s, s, smp, smp, s, s, s});
    trace_ = Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/ddgi/ddgi_trace.comp", defines), b,
                               sizeof(gpu::DdgiTracePush));
    auto with_texels = [](uint32_t n, bool distance) {
      std::vector<ShaderDefine> d = {{"GIQ_DDGI_TEXELS", std::to_string(n)}};
      if (distance) d.push_back({"GIQ_DDGI_DISTANCE"});
      return d;
    };
    for (int distance = 0; distance < 2; ++distance) {
      const uint32_t n = distance ? distance_texels_ : irradiance_texels_;
      blend_[distance] = Pipeline::compute(
          ci.ctx, ci.compiler.compile("techniques/ddgi/ddgi_blend.comp", with_texels(n, distance)),
          {s, s, s, img, s}, sizeof(gpu::DdgiBlendPush));
      border_[distance] = Pipeline::compute(
          ci.ctx, ci.compiler.compile("techniques/ddgi/ddgi_border.comp", with_texels(n, distance)),
          {s, s, img}, 0);
    }
    probes_ = Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/ddgi/ddgi_probes.comp"), {s, s, s, s},
                                sizeof(gpu::DdgiProbePush));
    b = GBufferPass::receiver_bindings();
    b.insert(b.end(), {s, s, smp, smp, img});
    shade_ = Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/ddgi/ddgi_shade.comp", defines), b,
                               sizeof(gpu::DdgiShadePush));
  }

  void record(const FrameInput& in, DeferredGi& frame) override {
    VkCommandBuffer cmd = in.cmd;
    if (in.frame == 0) {  // no history: black maps, probes at their grid positions, active
      const float zero[4] = {0, 0, 0, 0};
      irradiance_.clear(cmd, zero);
      distance_.clear(cmd, zero);
      vkCmdFillBuffer(cmd, probe_buffer_.handle(), 0, VK_WHOLE_SIZE, 0);
      vkCmdFillBuffer(cmd, history_buffer_.handle(), 0, VK_WHOLE_SIZE, 0);
      full_barrier(cmd);
    }
    irradiance_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    distance_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    glm::vec4 rotation[3];
    random_rotation(in.frame, rotation);
    const uint32_t probes = volume_.counts.w;
    const uint32_t gy = std::min(probes, kMaxGroups), gz = (probes + gy - 1) / gy;

    in.timer.begin(cmd, "ddgi_trace");
    gpu::DdgiTracePush tp{};
    std::copy(rotation, rotation + 3, tp.rotation);
    tp.environment = glm::vec4(in.scene.environment, float(in.scene.environment_map));
    tp.light_count = scene_gpu_.light_count();
    tp.area_light_count = uint32_t(frame.direct_light().area_lights().size());
    // The first frame has no irradiance to feed back.
    tp.feedback = feedback_ && in.frame > 0 ? 1u : 0u;
    tp.albedo_cap = kAlbedoCap;
    trace_.bind(cmd);
    auto d = scene_gpu_.descriptors();
    d.insert(d.end(), {Descriptor::storage(volume_buffer_), Descriptor::storage(probe_buffer_),
                       Descriptor::sampled(irradiance_, sampler_), Descriptor::sampled(distance_, sampler_),
                       Descriptor::storage(frame.direct_light().area_light_buffer()),
                       Descriptor::storage(frame.direct_light().area_triangle_buffer()),
                       Descriptor::storage(ray_buffer_)});
    trace_.push_descriptors(cmd, d);
    trace_.push_constants(cmd, tp);
    vkCmdDispatch(cmd, (rays_ + 63) / 64, gy, gz);
    full_barrier(cmd);
    in.timer.end(cmd);

    in.timer.begin(cmd, "ddgi_blend");
    gpu::DdgiBlendPush bp{};
    std::copy(rotation, rotation + 3, bp.rotation);
    bp.hysteresis = hysteresis_;
    bp.change_threshold = kChangeThreshold;
    bp.brightness_threshold = kBrightnessThreshold;
    Image* atlases[2] = {&irradiance_, &distance_};
    const uint32_t bx = std::min(probes, kMaxGroups), by = (probes + bx - 1) / bx;
    for (int i = 0; i < 2; ++i) {
      blend_[i].bind(cmd);
      blend_[i].push_descriptors(cmd, {Descriptor::storage(volume_buffer_), Descriptor::storage(probe_buffer_),
                                       Descriptor::storage(ray_buffer_), Descriptor::storage_image(*atlases[i]),
                                       Descriptor::storage(history_buffer_)});
      blend_[i].push_constants(cmd, bp);
      vkCmdDispatch(cmd, bx, by, 1);
    }
    full_barrier(cmd);
    for (int i = 0; i < 2; ++i) {
      border_[i].bind(cmd);
      border_[i].push_descriptors(cmd, {Descriptor::storage(volume_buffer_), Descriptor::storage(probe_buffer_),
                                        Descriptor::storage_image(*atlases[i])});
      border_[i].dispatch_2d(cmd, atlases[i]->desc().width, atlases[i]->desc().height);
    }
    full_barrier(cmd);
    in.timer.end(cmd);

    in.timer.begin(cmd, "ddgi_probes");
    gpu::DdgiProbePush pp{};
    pp.backface_threshold = kBackfaceThreshold;
    pp.min_frontface = 0.2f * volume_.origin.w;
    pp.max_offset = 0.45f * volume_.origin.w;
    probes_.bind(cmd);
    probes_.push_descriptors(cmd, {Descriptor::storage(volume_buffer_), Descriptor::storage(probe_buffer_),
                                   Descriptor::storage(ray_buffer_), Descriptor::storage(history_buffer_)});
    probes_.push_constants(cmd, pp);
    vkCmdDispatch(cmd, (probes + 63) / 64, 1, 1);
    full_barrier(cmd);
    in.timer.end(cmd);

    in.timer.begin(cmd, "ddgi_shade");
    Image& target = frame.indirect_target();
    target.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    shade_.bind(cmd);
    d = frame.gbuffer().receiver_descriptors();
    d.insert(d.end(), {Descriptor::storage(volume_buffer_), Descriptor::storage(probe_buffer_),
                       Descriptor::sampled(irradiance_, sampler_), Descriptor::sampled(distance_, sampler_),
                       Descriptor::storage_image(target)});
    shade_.push_descriptors(cmd, d);
    gpu::DdgiShadePush sp{};
    sp.eye = gpu::gpu_eye(in.camera);
    sp.size = glm::uvec2(frame.width(), frame.height());
    shade_.push_constants(cmd, sp);
    shade_.dispatch_2d(cmd, frame.width(), frame.height());
    full_barrier(cmd);
    in.timer.end(cmd);
  }

 private:
  // The grid: `probe_grid` probes along the scene's largest side, as many at the same spacing
  // along the others, centred on the bounds (cell-centred: a box whose side is a whole number
  // of spacings gets probes half a spacing inside its walls, not on them), and `probe_padding`
  // more on each side of every axis. Spacing grows until every probe's data fits the memory
  // budget.
  void fit_volume(const TechniqueCreateInfo& ci, const ParameterValues& p) {
    const scenes::Bounds& bounds = ci.scene.bounds;
    const uint64_t budget = uint64_t(p.get("probe_budget_mb") * double(1 << 20));
    const uint64_t per_probe = probe_bytes(irradiance_texels_, distance_texels_, rays_);
    float spacing = bounds.largest_side() / float(p.get_int("probe_grid"));
    const uint32_t padding = uint32_t(p.get_int("probe_padding"));
    glm::uvec3 counts;
    for (;;) {
      for (int a = 0; a < 3; ++a)
        counts[a] = std::max(1u, uint32_t(std::ceil(double(bounds.extent()[a]) / spacing - 1e-3))) + 2u * padding;
      const uint64_t total = uint64_t(counts.x) * counts.y * counts.z;
      if (total * per_probe <= budget) break;
      if (total == 1)
        throw InputError("", "--param", "probe_budget_mb=" + std::to_string(p.get("probe_budget_mb")) +
                                            " holds no probe of " + std::to_string(per_probe) + " bytes");
      spacing *= 1.05f;
    }
    const uint32_t total = counts.x * counts.y * counts.z;
    // Tiles in rows no wider than the device's largest image.
    const uint32_t max_dim = ci.ctx.properties().limits.maxImageDimension2D;
    const uint32_t per_row = std::min(total, max_dim / (distance_texels_ + 2));
    const uint32_t rows = (total + per_row - 1) / per_row;
    if (uint64_t(rows) * (distance_texels_ + 2) > max_dim)
      throw InputError("", "--param", std::to_string(total) + " probes do not fit this device's " +
                                          std::to_string(max_dim) + "-texel atlases; lower probe_grid");
    volume_.origin = glm::vec4(bounds.centre() - 0.5f * spacing * glm::vec3(counts - 1u), spacing);
    volume_.counts = glm::uvec4(counts, total);
    volume_.tiles = glm::uvec4(per_row, irradiance_texels_, distance_texels_, rays_);
    volume_.bias = glm::vec4(float(p.get("normal_bias")) * spacing, float(p.get("view_bias")) * spacing,
                             // The distance moments saturate beyond 1.5 diagonals of a cell.
                             1.5f * std::sqrt(3.0f) * spacing, float(p.get("irradiance_gamma")));
    volume_.switches = glm::uvec4(p.get_int("visibility"), p.get_int("relocation"), p.get_int("classification"), 0);
  }

  const SceneGpu& scene_gpu_;
  uint32_t rays_ = 256, irradiance_texels_ = 6, distance_texels_ = 14;
  float hysteresis_ = 0.97f;
  bool feedback_ = true;
  gpu::GpuDdgiVolume volume_{};
  Image irradiance_, distance_;
  Buffer volume_buffer_, probe_buffer_, history_buffer_, ray_buffer_;
  Sampler sampler_;
  Pipeline trace_, blend_[2], border_[2], probes_, shade_;
};

}  // namespace

TechniqueInfo ddgi_technique() {
  TechniqueInfo info = deferred_technique<Ddgi>(
      "ddgi",
      "Dynamic Diffuse GI (Majercik et al. 2019, 2021): a probe grid over the scene, rays per probe through the "
      "compute BVH each frame, octahedral irradiance and distance-moment maps blended with hysteresis, Chebyshev "
      "visibility, probe relocation and classification",
      FrameNeeds{},
      {{"probe_grid", 8, 2, 64, true,
        "probes along the scene's largest side (spacing = largest side / probe_grid; the other axes at the "
        "same spacing)"},
       {"probe_padding", 0, 0, 4, true,
        "probe spacings added beyond the scene's bounds on every side: 0 fits the bounds (a room), 1 or more puts "
        "probes around an object alone in space"},
       {"probe_budget_mb", 256, 1, 4096, false,
        "largest memory for the probes' maps and rays, MiB; the spacing grows until they fit"},
       {"rays_per_probe", 256, 64, 1024, true,
        "rays each probe traces per frame, the first 32 fixed (relocation and classification only)"},
       {"hysteresis", 0.97, 0, 0.999, false, "weight of a probe texel's history in each frame's blend"},
       {"irradiance_texels", 6, 2, 16, true, "interior texels per side of a probe's octahedral irradiance map"},
       {"distance_texels", 14, 2, 32, true, "interior texels per side of a probe's distance-moment map"},
       {"irradiance_gamma", 5, 1, 10, false,
        "irradiance is stored and blended as E^(1/gamma) (the papers' perceptual encoding); 1 = linear"},
       {"normal_bias", 0.1, 0, 1, false, "the query point moves off the surface by this, in probe spacings"},
       {"view_bias", 0.1, 0, 1, false, "the query point moves towards the viewer by this, in probe spacings"},
       {"visibility", 1, 0, 1, true, "1: Chebyshev visibility from the distance moments; 0: off (leaks)"},
       {"relocation", 1, 0, 1, true, "1: probes move out of geometry and away from close surfaces"},
       {"classification", 1, 0, 1, true, "1: probes inside geometry or far from every surface are switched off"},
       {"feedback", 1, 0, 1, true,
        "1: probe rays see the volume's irradiance at their hits (multi-bounce); 0: one bounce"}},
      {"probe_grid", {4, 6, 8, 12, 16, 24}});
  info.lights_with_environment = true;  // probe rays that miss see it (docs/techniques/ddgi.md)
  return info;
}

}  // namespace giq::realtime
