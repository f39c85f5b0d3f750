#pragma once
// GPU timestamps per pass and the statistics written to timings.json.
//
// Each pass is bracketed by two timestamps, each behind a full barrier: a pass's time is its
// own work, never overlapped with its neighbours'. A frame's GPU time runs from the first
// pass's start to the last pass's end. (Serialising passes costs a GPU that could overlap
// them a little time; that is the honest price of per-pass numbers.)

#include <vulkan/vulkan.h>

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace giq::realtime {

class Context;

class GpuTimer {
 public:
  explicit GpuTimer(Context& ctx, uint32_t max_passes = 64);
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  // Starts a frame's recording: forgets the previous frame's passes.
  void reset(VkCommandBuffer cmd);
  void begin(VkCommandBuffer cmd, const std::string& pass);
  void end(VkCommandBuffer cmd);
  // After the frame's commands have completed: milliseconds per pass, in recording order.
  std::vector<std::pair<std::string, double>> resolve() const;
  // Milliseconds from the first begin to the last end.
  double frame_ms() const;

 private:
  Context& ctx_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t capacity_;
  std::vector<std::string> passes_;
  bool open_ = false;
  std::vector<uint64_t> read() const;
};

// Median, mean and percentiles of a set of samples (linear interpolation between order
// statistics, Hyndman and Fan 1996 type 7, the numpy default).
nlohmann::json summarize(std::vector<double> samples);
double percentile(std::vector<double> sorted_samples, double p);

struct FrameTiming {
  int frame = 0;
  bool warmup = false;
  double gpu_ms = 0.0;
  double cpu_ms = 0.0;  // wall time of recording, submission and wait, excluding read-back
  std::vector<std::pair<std::string, double>> passes;
};

// timings.json: see docs/realtime.md for the format.
nlohmann::json timings_json(const std::vector<FrameTiming>& frames, const nlohmann::json& run_info);

}  // namespace giq::realtime
