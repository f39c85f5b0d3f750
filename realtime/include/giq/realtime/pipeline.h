#pragma once
// Compute and graphics pipelines with one push-descriptor set (binding i = the i-th entry of
// the layout) and push constants. Push descriptors (VK_KHR_push_descriptor, on lavapipe and
// NVIDIA alike) keep passes free of descriptor pools; no descriptor indexing is used, which
// lavapipe lacks. Graphics pipelines pull vertices from storage buffers by gl_VertexIndex, so
// they have no vertex input state, and use dynamic rendering (no render pass objects).

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace giq::realtime {

class Context;
class Buffer;
class Image;
class Sampler;

struct Descriptor {
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  VkDescriptorBufferInfo buffer{};
  VkDescriptorImageInfo image{};

  static Descriptor storage(const Buffer& b);
  static Descriptor storage_image(const Image& i);  // the image must be in GENERAL layout
  static Descriptor storage_image(const Image& i, uint32_t level);  // one mip level, GENERAL
  static Descriptor sampled(const Image& i, const Sampler& s);
};

struct GraphicsDesc {
  std::vector<uint32_t> vertex_spirv;
  std::vector<uint32_t> fragment_spirv;  // empty: depth-only
  std::vector<VkFormat> color_formats;
  VkFormat depth_format = VK_FORMAT_D32_SFLOAT;
  bool depth_bias = false;  // dynamic depth bias (shadow maps)
};

class Pipeline {
 public:
  Pipeline() = default;
  static Pipeline compute(Context& ctx, const std::vector<uint32_t>& spirv,
                          const std::vector<VkDescriptorType>& bindings, uint32_t push_constant_bytes);
  static Pipeline graphics(Context& ctx, const GraphicsDesc& desc, const std::vector<VkDescriptorType>& bindings,
                           uint32_t push_constant_bytes);
  ~Pipeline();
  Pipeline(Pipeline&& o) noexcept;
  Pipeline& operator=(Pipeline&& o) noexcept;
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  void bind(VkCommandBuffer cmd) const;
  // Pushes descriptors for bindings 0..n-1, in order.
  void push_descriptors(VkCommandBuffer cmd, const std::vector<Descriptor>& descriptors) const;
  void push_constants(VkCommandBuffer cmd, const void* data, uint32_t bytes) const;
  template <class T>
  void push_constants(VkCommandBuffer cmd, const T& value) const {
    push_constants(cmd, &value, sizeof(T));
  }
  // Dispatches enough 8x8 (or `local` sized) groups to cover width x height.
  void dispatch_2d(VkCommandBuffer cmd, uint32_t width, uint32_t height, uint32_t local = 8) const;
  // Dispatches enough groups of `local` invocations to cover `count` items, folded into rows
  // of at most 65535 groups (the guaranteed maxComputeWorkGroupCount): the shader's item is
  // (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * local + gl_LocalInvocationID.x.
  void dispatch_1d(VkCommandBuffer cmd, uint64_t count, uint32_t local = 64) const;

 private:
  void release();
  void make_layout(const std::vector<VkDescriptorType>& bindings, uint32_t push_constant_bytes);
  Context* ctx_ = nullptr;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineBindPoint bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
  VkShaderStageFlags stages_ = 0;
  std::vector<VkDescriptorType> bindings_;
};

}  // namespace giq::realtime
