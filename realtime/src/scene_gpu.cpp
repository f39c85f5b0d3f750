#include "giq/realtime/scene_gpu.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "giq/base/error.h"
#include "giq/realtime/context.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "scene_gpu_rows.h"
#include "shaders/particles_shared.h"
#include "shaders/scene_shared.h"

namespace giq::realtime {

FlatGeometry flatten(const scenes::Scene& scene, bool placed) {
  FlatGeometry g;
  // Allocated once: a large file's arrays would otherwise spend their time regrowing, every
  // frame the scene is posed.
  size_t vertices = 0, triangles = 0;
  for (const auto& m : scene.meshes)
    if (m.emitter < 0 || placed) vertices += m.positions.size(), triangles += m.triangles.size();
  g.positions.reserve(vertices);
  g.normals.reserve(vertices);
  g.triangles.reserve(triangles);
  g.material.reserve(triangles);
  g.object_id.reserve(triangles);
  bool stages = false;
  for (const auto& m : scene.meshes) {
    // The GPU writes the particles after the file's part of every array (SceneGpu::update).
    if (m.emitter < 0 && stages)
      throw std::logic_error("flatten: mesh '" + m.name + "' follows the particles' stages; a posed scene lists them last (scenes::Scene::at)");
    stages = stages || m.emitter >= 0;
    if (m.emitter >= 0 && !placed) {
      add_stage_places(m, g);
      continue;
    }
    const uint32_t base = g.vertex_count;
    g.mesh_first_triangle.push_back(g.triangle_count);
    g.mesh_first_vertex.push_back(base);
    g.vertex_count += uint32_t(m.positions.size());
    g.triangle_count += uint32_t(m.triangles.size());
    for (size_t i = 0; i < m.positions.size(); ++i) {
      g.positions.push_back(m.positions[i]);
      g.normals.push_back(i < m.normals.size() ? m.normals[i] : glm::vec3(0.0f));
    }
    for (const auto& t : m.triangles) {
      g.triangles.push_back(t + glm::uvec3(base));
      g.material.push_back(uint32_t(m.material));
      g.object_id.push_back(m.object_id);
    }
  }
  return g;
}

glm::uvec4 own_geometry(const scenes::Scene& scene, const FlatGeometry& g, uint32_t mesh) {
  size_t first = mesh, end = size_t(mesh) + 1;
  if (scene.meshes[mesh].emitter >= 0) {
    while (first > 0 && scene.meshes[first - 1].emitter >= 0) --first;
    while (end < scene.meshes.size() && scene.meshes[end].emitter >= 0) ++end;
  }
  auto vertex = [&](size_t m) { return m < g.mesh_first_vertex.size() ? g.mesh_first_vertex[m] : g.vertex_count; };
  auto triangle = [&](size_t m) { return m < g.mesh_first_triangle.size() ? g.mesh_first_triangle[m] : g.triangle_count; };
  return {vertex(first), vertex(end) - vertex(first), triangle(first), triangle(end) - triangle(first)};
}

namespace {

uint32_t wrap_code(scenes::Wrap w) {
  return w == scenes::Wrap::Repeat ? GIQ_WRAP_REPEAT : w == scenes::Wrap::ClampToEdge ? GIQ_WRAP_CLAMP : GIQ_WRAP_MIRROR;
}

uint32_t format_code(scenes::TexelFormat f) {
  return f == scenes::TexelFormat::Rgba8Srgb ? GIQ_TEXELS_RGBA8_SRGB : f == scenes::TexelFormat::Rgba8Unorm ? GIQ_TEXELS_RGBA8_UNORM : GIQ_TEXELS_RGBA32F;
}

}  // namespace

TexelPacking pack_texels(const std::vector<uint64_t>& words, uint64_t chunk_words) {
  TexelPacking p;
  for (uint64_t n : words) {
    if (n == 0 || n > chunk_words) {
      p.chunk.push_back(n == 0 ? 0 : -1);
      p.first_word.push_back(0);
      if (p.chunk_words.empty()) p.chunk_words.push_back(0);
      continue;
    }
    // Next fit: textures stay in scene order, a new chunk opens when one is full.
    if (p.chunk_words.empty() || p.chunk_words.back() + n > chunk_words) p.chunk_words.push_back(0);
    p.chunk.push_back(int(p.chunk_words.size() - 1));
    p.first_word.push_back(p.chunk_words.back());
    p.chunk_words.back() += n;
  }
  return p;
}

uint32_t mip_levels(uint32_t width, uint32_t height) { return uint32_t(std::bit_width(std::max({width, height, 1u}))); }

uint64_t mip_chain_texels(uint32_t width, uint32_t height, uint32_t levels) {
  uint64_t n = 0;
  for (uint32_t l = 0; l < levels; ++l) n += uint64_t(std::max(1u, width >> l)) * std::max(1u, height >> l);
  return n;
}

SceneGpu::SceneGpu(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& scene)
    : ctx_(&ctx), compiler_(&compiler), features_(scene.features) {
  std::vector<uint32_t> levels;
  upload_materials(scene, levels);
  uint32_t most_particles = 0;
  for (const scenes::Emitter& e : scene.emitters) {
    particles_.push_back(std::make_unique<ParticleSystem>(ctx, compiler, e));
    most_particles += particles_.back()->capacity();
  }
  if (!particles_.empty()) {
    particle_bvh_ = std::make_unique<LinearBvh>(ctx, compiler, most_particles, scenes::kParticleTriangles);
    particle_bounds_ = std::make_unique<ParticleBounds>(ctx, compiler);
    // The stages' materials follow one another, emitter by emitter (scenes::complete_emitter).
    bool glows = false;
    uint32_t stages = 0;
    for (const scenes::Emitter& e : scene.emitters) {
      for (int s = 0; s < e.stages; ++s) glows |= scene.materials[size_t(e.first_material + s)].is_emissive();
      stages += uint32_t(e.stages);
    }
    stage_material_ = uint32_t(scene.emitters.front().first_material);
    if (glows && stages <= LinearBvh::kLightStages) {
      light_bvh_ = std::make_unique<LinearBvh>(ctx, compiler, most_particles, scenes::kParticleTriangles, true, particle_bvh_.get());
      light_tree_ = light_bvh_->make_light_tree(ctx);
    }
  }
  upload_geometry(scene, flatten(scene));
  grow(previous_vertices_, uint64_t(geometry_.vertex_count) * sizeof(gpu::GpuVertex), 0);
  if (!vertices_host_.empty()) previous_vertices_.upload(vertices_host_.data(), vertices_host_.size() * sizeof(glm::vec4));
  make_deformer(scene);
  prepare_particles(scene);
  if (deformer_ || !particles_.empty())
    ctx.submit_and_wait([&](VkCommandBuffer cmd) {
      record_particles(cmd, scene);
      record_deformation(cmd, false, true);
    });
  upload_lights(scene);
  make_mips(compiler, scene, levels);
}

SceneGpu::~SceneGpu() = default;

std::vector<glm::vec4> SceneGpu::vertex_rows(const FlatGeometry& g) {
  static_assert(sizeof(gpu::GpuVertex) == 2 * sizeof(glm::vec4));
  std::vector<glm::vec4> rows;
  rows.reserve(2 * g.positions.size());
  for (size_t i = 0; i < g.positions.size(); ++i) rows.insert(rows.end(), {glm::vec4(g.positions[i], 1.0f), glm::vec4(g.normals[i], 0.0f)});
  return rows;
}

std::vector<VkBufferCopy> SceneGpu::rigid_ranges(const scenes::Scene& scene, const FlatGeometry& g) {
  std::vector<VkBufferCopy> ranges;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    if (scene.meshes[m].deformation || scene.meshes[m].emitter >= 0) continue;
    const uint64_t first = g.mesh_first_vertex[m] * sizeof(gpu::GpuVertex);
    const uint64_t bytes = scene.meshes[m].positions.size() * sizeof(gpu::GpuVertex);
    if (!ranges.empty() && ranges.back().dstOffset + ranges.back().size == first)
      ranges.back().size += bytes;
    else
      ranges.push_back({first, first, bytes});
  }
  return ranges;
}

bool SceneGpu::grow(Buffer& buffer, uint64_t bytes, uint64_t keep, VkBufferUsageFlags extra) {
  bytes = std::max<uint64_t>(bytes, 16);
  if (buffer.size() >= bytes) return false;
  // Twice what is needed when the count may grow again (particles, or a buffer that has
  // grown), so that it rarely moves.
  const uint64_t size = particles_.empty() && !buffer ? bytes : 2 * bytes;
  Buffer bigger(*ctx_, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | extra);
  const VkBufferCopy kept{0, 0, std::min(keep, buffer.size())};
  if (kept.size > 0) ctx_->submit_and_wait([&](VkCommandBuffer cmd) { vkCmdCopyBuffer(cmd, buffer.handle(), bigger.handle(), 1, &kept); });
  buffer = std::move(bigger);
  return true;
}

void SceneGpu::make_deformer(const scenes::Scene& scene) {
  deformer_.reset();
  if (std::none_of(scene.meshes.begin(), scene.meshes.end(), [](const scenes::Mesh& m) { return m.deformation.has_value(); })) return;
  rigid_ranges_ = rigid_ranges(scene, geometry_);
  deformer_ = std::make_unique<Deformer>(*ctx_, *compiler_, scene, geometry_, needs_textures(scene.features));
  if (refitter_) return;
  refitter_ = std::make_unique<BvhRefitter>(*ctx_, *compiler_);
  refitter_->set_tree(bvh_, particle_bvh_ ? 1 : 0);
}

void SceneGpu::record_deformation(VkCommandBuffer cmd, bool save_previous, bool refit, GpuTimer* timer) const {
  if (!deformer_) return;
  if (timer) timer->begin(cmd, "deform");
  deformer_->record(cmd, vertices_, previous_vertices_, vertex_extra_, save_previous);
  if (timer) timer->end(cmd);
  full_barrier(cmd);
  if (!refit) return;
  if (timer) timer->begin(cmd, "bvh refit");
  refitter_->record(cmd, vertices_, triangles_, nodes_, prims_);
  if (timer) timer->end(cmd);
}

void SceneGpu::upload_geometry(const scenes::Scene& scene, FlatGeometry flat, bool may_refit, bool keep_deformed, bool file_moved) {
  using namespace gpu;
  Context& ctx = *ctx_;
  geometry_ = std::move(flat);
  bounds_ = scene.bounds;
  triangle_count_ = geometry_.triangle_count;
  fixed_triangles_ = uint32_t(geometry_.triangles.size());
  const uint64_t fixed_vertices = geometry_.positions.size();
  if (file_moved) {
    // Moved triangles keep the tree and refit its bounds, until the motion has made it
    // kMaxRefitCost times as costly to traverse as a fresh build (bench/results: refit
    // against build in time and in cost).
    last_bvh_update_ = BvhUpdate::Built;
    if (may_refit) {
      refit_bvh(bvh_, geometry_.positions, geometry_.triangles);
      if (sah_cost(bvh_) <= kMaxRefitCost * built_cost_) last_bvh_update_ = BvhUpdate::Refitted;
    }
    if (last_bvh_update_ == BvhUpdate::Built) {
      bvh_ = build_bvh(geometry_.positions, geometry_.triangles);
      built_cost_ = sah_cost(bvh_);
      if (refitter_) refitter_->set_tree(bvh_, particle_bvh_ ? 1 : 0);
    }
    vertices_host_ = vertex_rows(geometry_);
  }

  // Emissive triangles: chosen by power, as the reference does; the CDF is accumulated in
  // double so that a million small lights still end at exactly 1. The particles' come after
  // the host's, written by the GPU (place_particle_stages); their power changes the host's
  // CDF, so the host's are listed whenever anything moved.
  auto listed = [&](const scenes::EmissiveTriangle& e) { return e.power > 0.0f && scene.meshes[e.mesh].emitter < 0; };
  double host = 0.0;
  uint32_t host_count = 0;
  for (const auto& e : scene.emissive_triangles)
    if (listed(e)) host += e.power, ++host_count;
  const double total = place_particle_stages(scene, host_count, host);
  std::vector<GpuEmissive> emissive;
  std::vector<uint32_t> emissive_of_triangle(file_moved ? fixed_triangles_ : 0, 0);
  if (file_moved) emissive_listed_.clear();
  double acc = 0.0;
  for (const auto& e : scene.emissive_triangles) {
    if (!listed(e)) continue;
    const uint32_t tri = geometry_.mesh_first_triangle[e.mesh] + e.triangle;
    acc += e.power;
    GpuEmissive g;
    g.triangle = glm::uvec4(tri, 0, 0, 0);
    g.radiance = glm::vec4(e.radiance, e.area);
    g.sampling = glm::vec4(float(acc / total), float(e.power / total), 0.0f, 0.0f);
    emissive.push_back(g);
    if (file_moved) emissive_of_triangle[tri] = uint32_t(emissive.size()), emissive_listed_.emplace_back(e.mesh, e.triangle);
  }
  if (!emissive.empty() && emissive_count_ == emissive.size()) emissive.back().sampling.x = 1.0f;

  // The arrays grow to hold the particles', keeping the file's part, which the host uploads
  // only when the file moved (a particle's vertex extras are the defaults, written once).
  const bool textured = needs_textures(scene.features);
  grow(vertices_, uint64_t(geometry_.vertex_count) * sizeof(GpuVertex), fixed_vertices * sizeof(GpuVertex));
  grow(triangles_, uint64_t(triangle_count_) * sizeof(GpuTriangle), uint64_t(fixed_triangles_) * sizeof(GpuTriangle));
  grow(indices_, 3 * uint64_t(triangle_count_) * sizeof(uint32_t), 3 * uint64_t(fixed_triangles_) * sizeof(uint32_t),
       VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  grow(emissive_, uint64_t(emissive_count_) * sizeof(GpuEmissive), 0);
  if (!emissive.empty()) emissive_.upload(emissive.data(), emissive.size() * sizeof(GpuEmissive));
  const GpuVertexExtra plain{glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(1.0f)};
  if (textured && grow(vertex_extra_, uint64_t(geometry_.vertex_count) * sizeof(GpuVertexExtra), fixed_vertices * sizeof(GpuVertexExtra))) {
    const std::vector<GpuVertexExtra> tail(vertex_extra_.size() / sizeof(GpuVertexExtra) - fixed_vertices, plain);
    if (!tail.empty()) vertex_extra_.upload(tail.data(), tail.size() * sizeof(GpuVertexExtra), fixed_vertices * sizeof(GpuVertexExtra));
  }
  if (!textured && !vertex_extra_) vertex_extra_ = Buffer::storage(ctx, std::vector<GpuVertexExtra>{});
  if (!file_moved) return;

  if (keep_deformed)
    vertices_.upload_ranges(vertices_host_.data(), rigid_ranges_);
  else if (!vertices_host_.empty())
    vertices_.upload(vertices_host_.data(), vertices_host_.size() * sizeof(glm::vec4));

  std::vector<GpuTriangle> triangles(fixed_triangles_);
  std::vector<uint32_t> indices;
  indices.reserve(3 * fixed_triangles_);
  for (uint32_t i = 0; i < fixed_triangles_; ++i) {
    const auto t = geometry_.triangles[i];
    triangles[i].v = glm::uvec4(t, geometry_.material[i]);
    triangles[i].extra = glm::uvec4(emissive_of_triangle[i], geometry_.object_id[i], 0, 0);
    indices.insert(indices.end(), {t.x, t.y, t.z});
  }
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const scenes::Mesh& mesh = scene.meshes[m];
    if (mesh.emitter >= 0) continue;
    const uint32_t flags = (mesh.uvs.size() == mesh.positions.size() && !mesh.uvs.empty() ? GIQ_TRIANGLE_HAS_UVS : 0u) |
                           (mesh.tangents.size() == mesh.positions.size() && !mesh.tangents.empty() ? GIQ_TRIANGLE_HAS_TANGENTS : 0u) |
                           (mesh.normals.size() == mesh.positions.size() && !mesh.normals.empty() ? GIQ_TRIANGLE_HAS_NORMALS : 0u) |
                           (mesh.colors.size() == mesh.positions.size() && !mesh.colors.empty() ? GIQ_TRIANGLE_HAS_COLORS : 0u) |
                           (mesh.uvs2.size() == mesh.positions.size() && !mesh.uvs2.empty() ? GIQ_TRIANGLE_HAS_UVS2 : 0u);
    const uint32_t first = geometry_.mesh_first_triangle[m];
    for (size_t t = 0; t < mesh.triangles.size(); ++t) triangles[first + t].extra.z = flags;
  }
  if (!triangles.empty()) {
    triangles_.upload(triangles.data(), triangles.size() * sizeof(GpuTriangle));
    indices_.upload(indices.data(), indices.size() * sizeof(uint32_t));
  }

  if (textured) {
    std::vector<GpuVertexExtra> vertex_extra;
    vertex_extra.reserve(fixed_vertices);
    for (const auto& mesh : scene.meshes)
      for (size_t i = 0; i < mesh.positions.size() && mesh.emitter < 0; ++i) vertex_extra.push_back(extra_row(mesh, i));
    if (!vertex_extra.empty()) vertex_extra_.upload(vertex_extra.data(), vertex_extra.size() * sizeof(GpuVertexExtra));
  }

  std::vector<BvhNode> tree = bvh_.nodes;
  std::vector<uint32_t> prims = bvh_.prims;
  if (particle_bvh_) particle_bvh_->place_beside(tree, prims);
  std::vector<GpuBvhNode> nodes(tree.size());
  static_assert(sizeof(GpuBvhNode) == sizeof(BvhNode));
  std::memcpy(nodes.data(), tree.data(), nodes.size() * sizeof(GpuBvhNode));
  nodes_ = Buffer::storage(ctx, nodes);
  prims_ = Buffer::storage(ctx, prims);
}

// Materials and textures do not move: uploaded once.
void SceneGpu::upload_materials(const scenes::Scene& scene, std::vector<uint32_t>& levels) {
  using namespace gpu;
  Context& ctx = *ctx_;
  std::vector<GpuTexture> textures;
  std::vector<float> table(1, 0.0f);
  if (needs_textures(scene.features)) {
    // Texel words decoded and filtered in the shader (shaders/textures.glsl) with
    // scenes::Texture::sample's arithmetic: no sampler or image array to bind, no descriptor
    // indexing, and the reference's floats to the bit. 8-bit texels become floats through
    // scenes::decode_table on both sides (bound as GIQ_BINDING_DECODE). Texels are read
    // through buffer device addresses, so their total is not bounded by maxStorageBufferRange
    // (128 MiB on lavapipe: eight 2048² textures): they are packed into as few buffers as
    // the device's largest allocation allows (pack_texels).
    table.assign(scenes::decode_table().begin(), scenes::decode_table().end());
    VkPhysicalDeviceMaintenance3Properties m3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &m3};
    vkGetPhysicalDeviceProperties2(ctx.physical_device(), &p2);
    const uint64_t chunk_bytes = std::min<uint64_t>(kTexelChunkBytes, m3.maxMemoryAllocationSize);
    // Mip levels where the sampler asks for them, for the G-buffer's primary hits
    // (docs/realtime.md): a third more texels. The environment map is read by rays only.
    std::vector<uint64_t> sizes;
    for (size_t i = 0; i < scene.textures.size(); ++i) {
      const auto& t = scene.textures[i];
      const bool mips = t.valid() && t.mip_maps && int(i) != scene.environment_map;
      levels.push_back(mips ? mip_levels(uint32_t(t.width), uint32_t(t.height)) : 1u);
      sizes.push_back(t.valid() ? mip_chain_texels(uint32_t(t.width), uint32_t(t.height), levels.back()) *
                                      scenes::Texture::words_per_texel(t.format)
                                : 0);
    }
    const TexelPacking packing = pack_texels(sizes, chunk_bytes / sizeof(uint32_t));
    for (size_t i = 0; i < sizes.size(); ++i)
      if (packing.chunk[i] < 0)
        throw InputError(scene.path.string(), "textures[" + std::to_string(i) + "]",
                         scene.textures[i].name + " takes " + std::to_string(sizes[i] * sizeof(uint32_t)) +
                             " bytes on the GPU; expected at most " + std::to_string(chunk_bytes) +
                             " bytes, this device's largest allocation");
    texture_bytes_ = 0;
    for (uint64_t words : packing.chunk_words) {
      texel_chunks_.emplace_back(ctx, std::max<uint64_t>(words, 1) * sizeof(uint32_t),
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
      texture_bytes_ += words * sizeof(uint32_t);
    }
    for (size_t i = 0; i < sizes.size(); ++i) {
      const auto& t = scene.textures[i];
      GpuTexture g;
      const bool valid = sizes[i] > 0;
      // A texture without texels samples as 0, like scenes::Texture::sample.
      g.info = glm::uvec4(levels[i], valid ? uint32_t(t.width) : 0u, valid ? uint32_t(t.height) : 0u,
                          wrap_code(t.wrap_s) | wrap_code(t.wrap_t) << 2 |
                              (t.filter == scenes::Filter::Linear ? GIQ_FILTER_LINEAR : GIQ_FILTER_NEAREST) << 4 |
                              format_code(t.format) << 5);
      if (valid) {
        Buffer& chunk = texel_chunks_[size_t(packing.chunk[i])];
        const uint64_t offset = packing.first_word[i] * sizeof(uint32_t);
        chunk.upload(t.words->data(), t.words->size() * sizeof(uint32_t), offset);
        const VkDeviceAddress a = chunk.address() + offset;
        g.texels = glm::uvec4(uint32_t(a), uint32_t(a >> 32), 0u, 0u);
      }
      textures.push_back(g);
    }
  }
  texture_bytes_ += table.size() * sizeof(float);
  texture_count_ = uint32_t(textures.size());

  std::vector<GpuMaterial> materials;
  for (const auto& m : scene.materials) {
    GpuMaterial g;
    g.base_color = m.base_color;
    g.emissive = glm::vec4(m.emissive, m.is_emissive() ? 1.0f : 0.0f);
    g.specular_color = glm::vec4(m.specular_color, 0.0f);
    g.params = glm::vec4(m.metallic, m.roughness, m.has_specular_lobe() ? m.specular : 0.0f, m.double_sided ? 1.0f : 0.0f);
    // Texture indices only where the scene's shaders compile texturing at all.
    const bool tex = needs_textures(scene.features);
    g.textures = tex ? glm::ivec4(m.base_color_texture, m.metallic_roughness_texture, m.emissive_texture, m.normal_texture)
                     : glm::ivec4(-1);
    g.textures2 = tex ? glm::ivec4(m.specular_texture, m.specular_color_texture, int(m.uv2_slots), -1) : glm::ivec4(-1, -1, 0, -1);
    const float mode = m.alpha_mode == scenes::AlphaMode::Mask ? 1.0f : m.alpha_mode == scenes::AlphaMode::Blend ? 2.0f : 0.0f;
    g.mask = glm::vec4(mode, m.alpha_cutoff, m.normal_scale, 0.0f);
    materials.push_back(g);
  }

  materials_ = Buffer::storage(ctx, materials);
  textures_ = Buffer::storage(ctx, textures);
  decode_ = Buffer::storage(ctx, table);
}

void SceneGpu::make_mips(ShaderCompiler& compiler, const scenes::Scene& scene, const std::vector<uint32_t>& levels) {
  const uint32_t most = levels.empty() ? 1u : *std::max_element(levels.begin(), levels.end());
  if (most <= 1) return;
  const Pipeline pipeline = Pipeline::compute(*ctx_, compiler.compile("shaders/texture_mips.comp"), binding_types(),
                                              2 * sizeof(uint32_t));
  // Level by level, every texture at once: level l reads level l - 1, written before the barrier.
  ctx_->submit_and_wait([&](VkCommandBuffer cmd) {
    pipeline.bind(cmd);
    pipeline.push_descriptors(cmd, descriptors());
    for (uint32_t level = 1; level < most; ++level) {
      for (size_t i = 0; i < levels.size(); ++i) {
        if (level >= levels[i]) continue;
        const uint32_t push[2] = {uint32_t(i), level};
        pipeline.push_constants(cmd, push, sizeof(push));
        const auto& t = scene.textures[i];
        pipeline.dispatch_2d(cmd, std::max(1u, uint32_t(t.width) >> level), std::max(1u, uint32_t(t.height) >> level));
      }
      full_barrier(cmd);
    }
  });
}

bool SceneGpu::upload_lights(const scenes::Scene& scene) {
  using namespace gpu;
  std::vector<GpuLight> lights;
  for (const auto& l : scene.lights) {
    GpuLight g;
    const float type = l.type == scenes::LightType::Directional ? GIQ_LIGHT_DIRECTIONAL
                       : l.type == scenes::LightType::Point     ? GIQ_LIGHT_POINT
                                                                : GIQ_LIGHT_SPOT;
    g.position = glm::vec4(l.position, type);
    g.direction = glm::vec4(glm::normalize(l.direction), l.range);
    g.radiant = glm::vec4(l.radiant(), 0.0f);
    // KHR_lights_punctual's recommended spot falloff, precomputed in the same float
    // arithmetic as scenes::spot_attenuation so the GPU evaluates the identical ramp.
    const float cos_outer = std::cos(l.outer_cone);
    const float scale = 1.0f / std::max(0.001f, std::cos(l.inner_cone) - cos_outer);
    g.cone = glm::vec4(scale, -cos_outer * scale, 0.0f, 0.0f);
    lights.push_back(g);
  }
  light_count_ = uint32_t(lights.size());
  static_assert(sizeof(GpuLight) % sizeof(glm::vec4) == 0);
  const size_t bytes = lights.size() * sizeof(GpuLight);
  // (memcmp and memcpy only with bytes: a scene without punctual lights has null data pointers.)
  if (lights_ && bytes == lights_host_.size() * sizeof(glm::vec4) &&
      (bytes == 0 || std::memcmp(lights.data(), lights_host_.data(), bytes) == 0))
    return false;
  lights_ = Buffer::storage(*ctx_, lights);
  lights_host_.resize(bytes / sizeof(glm::vec4));
  if (bytes) std::memcpy(lights_host_.data(), lights.data(), bytes);
  return true;
}

std::vector<VkDescriptorType> SceneGpu::binding_types() {
  return std::vector<VkDescriptorType>(GIQ_SCENE_BINDING_COUNT, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

std::vector<Descriptor> SceneGpu::descriptors() const {
  return {Descriptor::storage(vertices_), Descriptor::storage(triangles_), Descriptor::storage(materials_),
          Descriptor::storage(nodes_),    Descriptor::storage(prims_),     Descriptor::storage(lights_),
          Descriptor::storage(emissive_), Descriptor::storage(vertex_extra_), Descriptor::storage(textures_),
          Descriptor::storage(decode_)};
}

}  // namespace giq::realtime
