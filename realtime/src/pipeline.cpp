#include "giq/realtime/pipeline.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "giq/realtime/context.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/vk.h"

namespace giq::realtime {

Descriptor Descriptor::storage(const Buffer& b) {
  Descriptor d;
  d.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  d.buffer = {b.handle(), 0, VK_WHOLE_SIZE};
  return d;
}

Descriptor Descriptor::storage_image(const Image& i) {
  Descriptor d;
  d.type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  d.image = {VK_NULL_HANDLE, i.view(), VK_IMAGE_LAYOUT_GENERAL};
  return d;
}

Descriptor Descriptor::storage_image(const Image& i, uint32_t level) {
  Descriptor d;
  d.type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  d.image = {VK_NULL_HANDLE, i.level_view(level), VK_IMAGE_LAYOUT_GENERAL};
  return d;
}

Descriptor Descriptor::sampled(const Image& i, const Sampler& s) {
  Descriptor d;
  d.type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  d.image = {s.handle(), i.view(), i.layout()};
  return d;
}

namespace {
VkShaderModule make_module(VkDevice device, const std::vector<uint32_t>& spirv) {
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = spirv.size() * sizeof(uint32_t);
  ci.pCode = spirv.data();
  VkShaderModule m;
  vk_check(vkCreateShaderModule(device, &ci, nullptr, &m), "vkCreateShaderModule");
  return m;
}
}  // namespace

void Pipeline::make_layout(const std::vector<VkDescriptorType>& bindings, uint32_t push_constant_bytes) {
  bindings_ = bindings;
  std::vector<VkDescriptorSetLayoutBinding> b(bindings.size());
  for (uint32_t i = 0; i < bindings.size(); ++i) b[i] = {i, bindings[i], 1, stages_, nullptr};
  VkDescriptorSetLayoutCreateInfo sci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  sci.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  sci.bindingCount = uint32_t(b.size());
  sci.pBindings = b.data();
  vk_check(vkCreateDescriptorSetLayout(ctx_->device(), &sci, nullptr, &set_layout_), "vkCreateDescriptorSetLayout");
  VkPushConstantRange range{stages_, 0, push_constant_bytes};
  VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  lci.setLayoutCount = 1;
  lci.pSetLayouts = &set_layout_;
  lci.pushConstantRangeCount = push_constant_bytes ? 1 : 0;
  lci.pPushConstantRanges = &range;
  vk_check(vkCreatePipelineLayout(ctx_->device(), &lci, nullptr, &layout_), "vkCreatePipelineLayout");
}

Pipeline Pipeline::compute(Context& ctx, const std::vector<uint32_t>& spirv, const std::vector<VkDescriptorType>& bindings,
                           uint32_t push_constant_bytes) {
  Pipeline p;
  p.ctx_ = &ctx;
  p.bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
  p.stages_ = VK_SHADER_STAGE_COMPUTE_BIT;
  p.make_layout(bindings, push_constant_bytes);
  VkShaderModule m = make_module(ctx.device(), spirv);
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = m;
  ci.stage.pName = "main";
  ci.layout = p.layout_;
  VkResult r = vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &p.pipeline_);
  vkDestroyShaderModule(ctx.device(), m, nullptr);
  vk_check(r, "vkCreateComputePipelines");
  return p;
}

Pipeline Pipeline::graphics(Context& ctx, const GraphicsDesc& desc, const std::vector<VkDescriptorType>& bindings,
                            uint32_t push_constant_bytes) {
  Pipeline p;
  p.ctx_ = &ctx;
  p.bind_point_ = VK_PIPELINE_BIND_POINT_GRAPHICS;
  p.stages_ = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  p.make_layout(bindings, push_constant_bytes);
  VkShaderModule vs = make_module(ctx.device(), desc.vertex_spirv);
  VkShaderModule fs = desc.fragment_spirv.empty() ? VK_NULL_HANDLE : make_module(ctx.device(), desc.fragment_spirv);
  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vs;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fs;
  stages[1].pName = "main";
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = VK_CULL_MODE_NONE;  // facing is resolved per material in the shaders
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.depthBiasEnable = desc.depth_bias;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = VK_TRUE;
  ds.depthWriteEnable = VK_TRUE;
  ds.depthCompareOp = VK_COMPARE_OP_LESS;
  std::vector<VkPipelineColorBlendAttachmentState> blend(desc.color_formats.size());
  for (auto& b : blend) b.colorWriteMask = 0xf;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = uint32_t(blend.size());
  cb.pAttachments = blend.data();
  std::vector<VkDynamicState> dyn = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  if (desc.depth_bias) dyn.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
  VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dy.dynamicStateCount = uint32_t(dyn.size());
  dy.pDynamicStates = dyn.data();
  VkPipelineRenderingCreateInfo ri{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  ri.colorAttachmentCount = uint32_t(desc.color_formats.size());
  ri.pColorAttachmentFormats = desc.color_formats.data();
  ri.depthAttachmentFormat = desc.depth_format;
  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &ri};
  ci.stageCount = fs ? 2 : 1;
  ci.pStages = stages;
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dy;
  ci.layout = p.layout_;
  VkResult r = vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &p.pipeline_);
  vkDestroyShaderModule(ctx.device(), vs, nullptr);
  if (fs) vkDestroyShaderModule(ctx.device(), fs, nullptr);
  vk_check(r, "vkCreateGraphicsPipelines");
  return p;
}

Pipeline::~Pipeline() { release(); }

void Pipeline::release() {
  if (!ctx_) return;
  if (pipeline_) vkDestroyPipeline(ctx_->device(), pipeline_, nullptr);
  if (layout_) vkDestroyPipelineLayout(ctx_->device(), layout_, nullptr);
  if (set_layout_) vkDestroyDescriptorSetLayout(ctx_->device(), set_layout_, nullptr);
  pipeline_ = VK_NULL_HANDLE, layout_ = VK_NULL_HANDLE, set_layout_ = VK_NULL_HANDLE, ctx_ = nullptr;
}

Pipeline::Pipeline(Pipeline&& o) noexcept { *this = std::move(o); }

Pipeline& Pipeline::operator=(Pipeline&& o) noexcept {
  if (this != &o) {
    release();
    ctx_ = std::exchange(o.ctx_, nullptr);
    set_layout_ = std::exchange(o.set_layout_, VK_NULL_HANDLE);
    layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
    pipeline_ = std::exchange(o.pipeline_, VK_NULL_HANDLE);
    bind_point_ = o.bind_point_;
    stages_ = o.stages_;
    bindings_ = std::move(o.bindings_);
  }
  return *this;
}

void Pipeline::bind(VkCommandBuffer cmd) const { vkCmdBindPipeline(cmd, bind_point_, pipeline_); }

void Pipeline::push_descriptors(VkCommandBuffer cmd, const std::vector<Descriptor>& descriptors) const {
  if (descriptors.size() != bindings_.size())
    throw std::logic_error("push_descriptors: " + std::to_string(descriptors.size()) + " descriptors for " +
                           std::to_string(bindings_.size()) + " bindings");
  std::vector<VkWriteDescriptorSet> w(descriptors.size());
  for (uint32_t i = 0; i < descriptors.size(); ++i) {
    if (descriptors[i].type != bindings_[i]) throw std::logic_error("push_descriptors: type mismatch at binding " + std::to_string(i));
    w[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w[i].dstBinding = i;
    w[i].descriptorCount = 1;
    w[i].descriptorType = bindings_[i];
    if (bindings_[i] == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)
      w[i].pBufferInfo = &descriptors[i].buffer;
    else
      w[i].pImageInfo = &descriptors[i].image;
  }
  ctx_->cmd_push_descriptor_set(cmd, bind_point_, layout_, 0, uint32_t(w.size()), w.data());
}

void Pipeline::push_constants(VkCommandBuffer cmd, const void* data, uint32_t bytes) const {
  vkCmdPushConstants(cmd, layout_, stages_, 0, bytes, data);
}

void Pipeline::dispatch_2d(VkCommandBuffer cmd, uint32_t width, uint32_t height, uint32_t local) const {
  vkCmdDispatch(cmd, (width + local - 1) / local, (height + local - 1) / local, 1);
}

void Pipeline::dispatch_1d(VkCommandBuffer cmd, uint64_t count, uint32_t local) const {
  const uint64_t groups = (count + local - 1) / local;
  if (groups == 0) return;
  const uint32_t x = uint32_t(std::min<uint64_t>(groups, 65535));
  vkCmdDispatch(cmd, x, uint32_t((groups + x - 1) / x), 1);
}

}  // namespace giq::realtime
