#pragma once
// What the texture tests share: their fixture (VulkanTest, whose render() draws a scene's
// first view), random 8-bit textures, and compute-shader queries against the scene's GPU
// buffers (a lookup, a mip level) read back for comparison with the scene library's own
// arithmetic.

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "giq/realtime/renderer.h"
#include "giq/realtime/shader.h"
#include "test_scenes.h"

namespace giq::test {

using TexturesTest = VulkanTest;

// An 8-bit texture of random texels (every byte pattern: sRGB, linear and alpha channels).
void add_random_texture(scenes::Scene& s, int w, int h, scenes::TexelFormat format, scenes::Filter filter,
                        scenes::Wrap wrap, std::mt19937& rng);

// Runs the compute shader `source` (local size 64; bindings: the scene's, then a read-only
// input buffer, then the output buffer) once per input element, with push constants `push`,
// on the scene uploaded as a technique sees it; returns the output buffer.
std::vector<uint8_t> scene_query(realtime::Context& ctx, realtime::ShaderCompiler& compiler, const scenes::Scene& s, const std::string& name,
                                 const std::string& source, const void* input, size_t input_bytes, size_t count,
                                 size_t output_bytes, const void* push, uint32_t push_bytes);

template <class Out, class In, class Push>
std::vector<Out> scene_query(realtime::Context& ctx, realtime::ShaderCompiler& compiler, const scenes::Scene& s, const std::string& name,
                             const std::string& source, const std::vector<In>& input, const Push& push) {
  const std::vector<uint8_t> bytes = scene_query(ctx, compiler, s, name, source, input.data(), input.size() * sizeof(In),
                                                 input.size(), input.size() * sizeof(Out), &push, sizeof(Push));
  std::vector<Out> out(input.size());
  std::copy(bytes.begin(), bytes.end(), reinterpret_cast<uint8_t*>(out.data()));
  return out;
}

// texture_sample (shaders/textures.glsl) at a batch of (u, v, texture, lod) queries, on the GPU.
std::vector<glm::vec4> sample_on_gpu(realtime::Context& ctx, realtime::ShaderCompiler& compiler, const scenes::Scene& s,
                                     const std::vector<glm::vec4>& queries);

}  // namespace giq::test
