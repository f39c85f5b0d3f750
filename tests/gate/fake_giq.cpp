// Test double for the giq subcommands that `giq gate` and `giq golden update` orchestrate:
// `reference`, `realtime` and `score` with the same flags, writing small files of the same
// shape (EXR frames, timings.json, metrics.json) instead of rendering. It lets the tests drive
// the orchestration (arguments, reuse, crashes, missing files, exit codes) without a GPU, a
// path tracer or real metrics. Used by tests only.
//
// Environment:
//   FAKE_GIQ_LOG        file to which every invocation appends its argument list (one line)
//   FAKE_GIQ_BEHAVIOUR  JSON file {"<case>": {"realtime": "ok"|"crash"|"no-frames",
//                                             "score": "ok"|"crash", "metrics": {...}}}
//                       where metrics.json is {"metrics": <metrics>} (a sequence case's
//                       "metrics" may hold "sequence"/"last_frame" itself: give "raw": {...};
//                       "echo_frames": true makes a score's sequence flicker its first frame
//                       and its lag its last, to show which frames a caller scored)
//   FAKE_GIQ_DEVICE     device name in timings.json (default "llvmpipe (LLVM 15.0.6, 256 bits)")
//   FAKE_GIQ_GPU_MS     frame_gpu_ms.median in timings.json (default 2.5)
//   FAKE_GIQ_REAL       a real giq binary: `score` of a case without fake metrics runs its
//                       `giq score` on the fake images (checks the gate reads real metrics.json)
//
// Images are 0.5 grey with a small variance layer (references); "realtime": "brighten" makes
// the technique's top-left quarter four times brighter.
//
// For sweeps it lists two techniques (`realtime --list --json`, in giq realtime's format). A frame
// rendered with parameters costs 1 + (sum of the values) ms, twice that for "pt", and the
// fake score of such a frame has flip_mean = 1 / (1 + sum), so every setting lies on a known
// curve. A reference records its spp; its fake rmse is 0.5 / sqrt(spp) and its render time
// 0.01 s per spp, so convergence slopes are exactly -1/2.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "giq/image/image.h"
#include "giq/image/io.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::map<std::string, std::vector<std::string>> parse(int argc, char** argv) {
  std::map<std::string, std::vector<std::string>> o;
  for (int i = 2; i < argc; ++i) {
    std::string k = argv[i];
    if (k.rfind("--", 0) != 0) continue;
    if (i + 1 < argc && std::string(argv[i + 1]).rfind("--", 0) != 0)
      o[k].push_back(argv[++i]);
    else
      o[k].push_back("");
  }
  return o;
}

std::string one(const std::map<std::string, std::vector<std::string>>& o, const std::string& k,
                const std::string& d = "") {
  const auto it = o.find(k);
  return it == o.end() || it->second.empty() ? d : it->second.back();
}

// The case name: the folder after "cases" in an output path.
std::string case_of(const fs::path& out) {
  std::string prev, name;
  for (const auto& part : out) {
    if (prev == "cases") name = part.string();
    prev = part.string();
  }
  return name;
}

json behaviour(const std::string& name) {
  const char* f = std::getenv("FAKE_GIQ_BEHAVIOUR");
  if (!f) return json::object();
  std::ifstream in(f);
  const json all = json::parse(in);
  return all.contains(name) ? all[name] : json::object();
}

void write_frame(const fs::path& p, int w, int h, const std::map<std::string, std::string>& meta,
                 bool variance = false, bool brighten = false) {
  giq::image::Image img(w, h);
  for (const char* c : {"R", "G", "B"}) {
    float* v = img.add_channel(c, 0.5f);
    if (brighten)
      for (int y = 0; y < h / 2; ++y)
        for (int x = 0; x < w / 2; ++x) v[size_t(y) * size_t(w) + size_t(x)] = 2.0f;
  }
  if (variance)
    for (const char* c : {"variance.R", "variance.G", "variance.B"}) img.add_channel(c, 1e-6f);
  img.metadata = meta;
  giq::image::write_exr(img, p);
}

std::string frame_file(int f) {
  char b[32];
  std::snprintf(b, sizeof b, "frame_%04d.exr", f);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  if (const char* log = std::getenv("FAKE_GIQ_LOG")) {
    std::ofstream l(log, std::ios::app);
    for (int i = 1; i < argc; ++i) l << (i > 1 ? " " : "") << argv[i];
    l << '\n';
  }
  const std::string cmd = argv[1];
  const auto o = parse(argc, argv);
  const int w = std::atoi(one(o, "--width", "8").c_str()),
            h = std::atoi(one(o, "--height", "8").c_str());
  if (cmd == "reference") {
    int a = 0, b = 0;
    std::sscanf(one(o, "--frames", "0:0").c_str(), "%d:%d", &a, &b);
    const std::string pattern = one(o, "--out");
    // '#'s stand for the frame number, zero-padded to their count, as giq reference's --out.
    const size_t hash = pattern.find('#');
    const size_t digits = hash == std::string::npos ? 0 : std::min(pattern.find_first_not_of('#', hash), pattern.size()) - hash;
    for (int f = a; f <= b; ++f) {
      char num[16];
      std::snprintf(num, sizeof num, "%0*d", int(digits), f);
      write_frame(
          hash == std::string::npos ? pattern
                                    : pattern.substr(0, hash) + num + pattern.substr(hash + digits),
          w, h,
          {{"giq.spp", one(o, "--spp", "77")},
           {"giq.version", "fake-reference"},
           // The header key as references before the unified key style wrote it: still read.
           {"giq.renderTime", std::to_string(0.01 * std::atof(one(o, "--spp", "77").c_str()))}},
          true);
    }
    return 0;
  }
  if (cmd == "realtime" && o.count("--list")) {
    std::printf("%s\n", R"({"version": 1, "techniques": [
      {"name": "direct", "description": "shadow maps", "parameters": [
        {"name": "pcf_radius", "default": 1, "min": 0, "max": 4, "integer": true, "description": "PCF kernel radius"},
        {"name": "normal_offset", "default": 1.5, "min": 0, "max": 8, "integer": false, "description": "texels"}],
       "quality": {"parameter": "pcf_radius", "values": [0, 1, 2]}},
      {"name": "pt", "description": "path tracer", "parameters": [
        {"name": "samples_per_frame", "default": 1, "min": 1, "max": 64, "integer": true, "description": "samples"}],
       "quality": {"parameter": "samples_per_frame", "values": [1, 4]}}]})");
    return 0;
  }
  if (cmd == "realtime") {
    const fs::path out = one(o, "--out");
    const json b = behaviour(case_of(out));
    const std::string mode = b.value("realtime", "ok");
    if (mode == "crash") std::abort();
    fs::create_directories(out);
    const int warmup = std::atoi(one(o, "--warmup", "0").c_str()),
              frames = std::atoi(one(o, "--frames", "1").c_str());
    double sum = 0.0;
    if (o.count("--param"))
      for (const std::string& p : o.at("--param"))
        sum += std::atof(p.substr(p.find('=') + 1).c_str());
    const std::string technique = one(o, "--technique");
    if (!o.count("--no-images") && mode != "no-frames")
      for (int f = warmup; f < warmup + frames; ++f)
        write_frame(out / frame_file(f), w, h,
                    {{"giq.technique", technique}, {"fake.sum", std::to_string(sum)}}, false,
                    mode == "brighten");
    const char* dev = std::getenv("FAKE_GIQ_DEVICE");
    const char* env_ms = std::getenv("FAKE_GIQ_GPU_MS");
    const double gpu = (technique == "pt" ? 2.0 : 1.0) * (1.0 + sum);
    const char* ms = env_ms ? env_ms : (o.count("--param") ? nullptr : "2.5");
    const json t = {{"device", {{"name", dev ? dev : "llvmpipe (LLVM 15.0.6, 256 bits)"}}},
                    {"frames", {{"warmup", warmup}, {"measured", frames}}},
                    {"frame_gpu_ms", {{"count", frames}, {"median", ms ? std::atof(ms) : gpu}}}};
    std::ofstream(out / "timings.json") << t.dump(2);
    return 0;
  }
  if (cmd == "score") {
    const fs::path out = one(o, "--out");
    const json b = behaviour(case_of(out));
    if (b.value("score", "ok") == "crash") std::abort();
    if (const char* real = std::getenv("FAKE_GIQ_REAL");
        real && !b.contains("metrics") && !b.contains("raw")) {
      std::vector<char*> args = {const_cast<char*>(real)};
      for (int i = 1; i < argc; ++i) args.push_back(argv[i]);
      args.push_back(nullptr);
      ::execv(real, args.data());
      std::perror("fake giq: execv");
      return 3;
    }
    for (const char* k : {"--ref", "--test"}) {
      std::string p = one(o, k);
      if (p.find('%') != std::string::npos) {
        int a = 0, e = 0;
        std::sscanf(one(o, "--frames").c_str(), "%d:%d", &a, &e);
        char buf[4096];
        std::snprintf(buf, sizeof buf, p.c_str(), a);
        p = buf;
      }
      if (!fs::exists(p)) {
        std::fprintf(stderr, "giq: error: %s: cannot open\n", p.c_str());
        return 2;
      }
    }
    fs::create_directories(out);
    json dflt = {{"relmse", {{"value", 0.01}}}};
    giq::image::Image test;
    if (one(o, "--test").find('%') == std::string::npos)
      test = giq::image::read_image(one(o, "--test"));
    if (test.metadata.count("fake.sum"))
      dflt["flip"] = {
          {"mean", {{"value", 1.0 / (1.0 + std::atof(test.metadata.at("fake.sum").c_str()))}}}};
    if (test.metadata.count("giq.spp"))
      dflt["rmse"] = {{"value", 0.5 / std::sqrt(std::atof(test.metadata.at("giq.spp").c_str()))}};
    json m = b.contains("raw") ? b["raw"] : json{{"metrics", b.value("metrics", dflt)}};
    if (b.value("echo_frames", false)) {
      int a = 0, e = 0;
      std::sscanf(one(o, "--frames").c_str(), "%d:%d", &a, &e);
      m["sequence"]["flicker"] = {{"value", a}};
      m["sequence"]["lag"] = {{"value_frames", e}};
    }
    m["inputs"] = {{"reference", one(o, "--ref")},
                   {"test", one(o, "--test")},
                   {"layer", one(o, "--layer", "beauty")}};
    std::ofstream(out / "metrics.json") << m.dump(2);
    return 0;
  }
  std::fprintf(stderr, "fake giq: unknown command %s\n", cmd.c_str());
  return 2;
}
