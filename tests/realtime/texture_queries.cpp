#include "texture_queries.h"

#include <cstring>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/scene_gpu.h"

namespace giq::test {

using namespace giq::realtime;

void add_random_texture(scenes::Scene& s, int w, int h, scenes::TexelFormat format, scenes::Filter filter,
                        scenes::Wrap wrap, std::mt19937& rng) {
  scenes::Texture t;
  t.width = w, t.height = h, t.format = format, t.filter = filter, t.wrap_s = t.wrap_t = wrap;
  auto words = std::make_shared<std::vector<uint32_t>>(size_t(w) * size_t(h));
  for (auto& word : *words) word = uint32_t(rng());
  t.words = words;
  s.textures.push_back(t);
}

std::vector<uint8_t> scene_query(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& s, const std::string& name,
                                 const std::string& source, const void* input, size_t input_bytes, size_t count,
                                 size_t output_bytes, const void* push, uint32_t push_bytes) {
  SceneGpu gpu(ctx, compiler, s);
  auto bindings = SceneGpu::binding_types();
  bindings.insert(bindings.end(), 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  const Pipeline pipeline =
      Pipeline::compute(ctx, compiler.compile_source(name, source, feature_defines(s.features)), bindings, push_bytes);
  Buffer in(ctx, std::max<size_t>(input_bytes, 16), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  in.upload(input, input_bytes);
  Buffer out(ctx, std::max<size_t>(output_bytes, 16), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Readback);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    pipeline.bind(cmd);
    auto d = gpu.descriptors();
    d.push_back(Descriptor::storage(in));
    d.push_back(Descriptor::storage(out));
    pipeline.push_descriptors(cmd, d);
    pipeline.push_constants(cmd, push, push_bytes);
    vkCmdDispatch(cmd, uint32_t((count + 63) / 64), 1, 1);
    full_barrier(cmd);
  });
  std::vector<uint8_t> r(output_bytes);
  std::memcpy(r.data(), out.mapped(), output_bytes);
  return r;
}

std::vector<glm::vec4> sample_on_gpu(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& s,
                                     const std::vector<glm::vec4>& queries) {
  const std::string src = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#include "shaders/textures.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = GIQ_SCENE_BINDING_COUNT) readonly buffer Queries { vec4 queries[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 1) writeonly buffer Results { vec4 results[]; };
layout(push_constant) uniform Push { uint count; } pc;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < pc.count) results[i] = texture_sample(int(queries[i].z), queries[i].xy, queries[i].w);
}
)";
  return scene_query<glm::vec4>(ctx, compiler, s, "tests/texture_query.comp", src, queries, uint32_t(queries.size()));
}

}  // namespace giq::test
