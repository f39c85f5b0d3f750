#include "giq/realtime/timer.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

#include "giq/realtime/context.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/vk.h"

namespace giq::realtime {

GpuTimer::GpuTimer(Context& ctx, uint32_t max_passes) : ctx_(ctx), capacity_(max_passes) {
  VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  ci.queryCount = 2 * max_passes;
  vk_check(vkCreateQueryPool(ctx.device(), &ci, nullptr, &pool_), "vkCreateQueryPool");
}

GpuTimer::~GpuTimer() { vkDestroyQueryPool(ctx_.device(), pool_, nullptr); }

void GpuTimer::reset(VkCommandBuffer cmd) {
  vkCmdResetQueryPool(cmd, pool_, 0, 2 * capacity_);
  passes_.clear();
  open_ = false;
}

void GpuTimer::begin(VkCommandBuffer cmd, const std::string& pass) {
  if (open_) throw std::logic_error("GpuTimer: pass '" + pass + "' begins inside '" + passes_.back() + "'");
  if (passes_.size() >= capacity_) throw std::logic_error("GpuTimer: more passes than the query pool holds");
  // Barriers on both sides pin the timestamp between the previous pass and this one. The
  // second is needed by lavapipe, which otherwise takes a timestamp that opens a command
  // buffer only when the following work has run (a compute-only frame then reads ~0 ms).
  full_barrier(cmd);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, uint32_t(2 * passes_.size()));
  full_barrier(cmd);
  passes_.push_back(pass);
  open_ = true;
}

void GpuTimer::end(VkCommandBuffer cmd) {
  if (!open_) throw std::logic_error("GpuTimer: end without begin");
  full_barrier(cmd);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, uint32_t(2 * passes_.size() - 1));
  open_ = false;
}

std::vector<uint64_t> GpuTimer::read() const {
  std::vector<uint64_t> t(2 * passes_.size());
  if (t.empty()) return t;
  vk_check(vkGetQueryPoolResults(ctx_.device(), pool_, 0, uint32_t(t.size()), t.size() * sizeof(uint64_t), t.data(),
                                 sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
           "vkGetQueryPoolResults");
  // Timestamps wrap at timestampValidBits; differences are taken modulo that.
  return t;
}

namespace {
double ticks_to_ms(uint64_t a, uint64_t b, uint32_t bits, double period_ns) {
  const uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
  return double((b - a) & mask) * period_ns * 1e-6;
}
}  // namespace

std::vector<std::pair<std::string, double>> GpuTimer::resolve() const {
  const auto t = read();
  std::vector<std::pair<std::string, double>> out;
  for (size_t i = 0; i < passes_.size(); ++i)
    out.emplace_back(passes_[i], ticks_to_ms(t[2 * i], t[2 * i + 1], ctx_.timestamp_valid_bits(), ctx_.timestamp_period_ns()));
  return out;
}

double GpuTimer::frame_ms() const {
  const auto t = read();
  if (t.empty()) return 0.0;
  return ticks_to_ms(t.front(), t.back(), ctx_.timestamp_valid_bits(), ctx_.timestamp_period_ns());
}

double percentile(std::vector<double> s, double p) {
  if (s.empty()) return 0.0;
  std::sort(s.begin(), s.end());
  const double h = (double(s.size()) - 1.0) * p;
  const size_t lo = size_t(std::floor(h));
  const size_t hi = std::min(lo + 1, s.size() - 1);
  return s[lo] + (h - double(lo)) * (s[hi] - s[lo]);
}

nlohmann::json summarize(std::vector<double> s) {
  nlohmann::json j;
  j["count"] = s.size();
  if (s.empty()) return j;
  std::sort(s.begin(), s.end());
  j["median"] = percentile(s, 0.5);
  j["mean"] = std::accumulate(s.begin(), s.end(), 0.0) / double(s.size());
  j["min"] = s.front();
  j["max"] = s.back();
  j["p05"] = percentile(s, 0.05);
  j["p95"] = percentile(s, 0.95);
  j["p99"] = percentile(s, 0.99);
  return j;
}

nlohmann::json timings_json(const std::vector<FrameTiming>& frames, const nlohmann::json& run_info) {
  nlohmann::json j = run_info;
  std::vector<double> gpu, cpu;
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> per_pass;
  nlohmann::json per_frame = nlohmann::json::array();
  int warmup = 0;
  for (const auto& f : frames) {
    nlohmann::json pf = {{"frame", f.frame}, {"warmup", f.warmup}, {"gpu_ms", f.gpu_ms}, {"cpu_ms", f.cpu_ms}};
    // A pass recorded several times in a frame counts as its sum; first-recorded order kept.
    std::vector<std::pair<std::string, double>> summed;
    for (const auto& [name, ms] : f.passes) {
      auto it = std::find_if(summed.begin(), summed.end(), [&](const auto& p) { return p.first == name; });
      if (it == summed.end()) summed.emplace_back(name, ms);
      else it->second += ms;
    }
    nlohmann::json passes = nlohmann::json::object();
    for (const auto& [name, ms] : summed) passes[name] = ms;
    pf["passes"] = passes;
    per_frame.push_back(pf);
    if (f.warmup) {
      ++warmup;
      continue;
    }
    gpu.push_back(f.gpu_ms);
    cpu.push_back(f.cpu_ms);
    for (const auto& [name, ms] : summed) {
      if (!per_pass.count(name)) order.push_back(name);
      per_pass[name].push_back(ms);
    }
  }
  j["frames"] = {{"warmup", warmup}, {"measured", gpu.size()}};
  j["frame_gpu_ms"] = summarize(gpu);
  j["frame_cpu_ms"] = summarize(cpu);
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& name : order) passes.push_back({{"name", name}, {"gpu_ms", summarize(per_pass[name])}});
  j["passes"] = passes;
  j["per_frame"] = per_frame;
  return j;
}

}  // namespace giq::realtime
