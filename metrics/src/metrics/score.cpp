#include "giq/metrics/score.h"

#include <cctype>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "giq/base/json.h"
#include "giq/base/staged_folder.h"
#include "giq/base/version.h"
#include "giq/image/io.h"
#include "giq/metrics/catalogue.h"
#include "score_image.h"

namespace giq::metrics {
namespace {

using nlohmann::json;

// Position and width of the one %d / %0Nd conversion, or npos. "%%" is a literal percent.
struct Conversion {
  size_t begin = std::string::npos, end = 0;
  int width = 0;
  bool zero = false;
};

Conversion parse_pattern(const std::string& p) {
  Conversion c;
  for (size_t i = 0; i < p.size(); ++i) {
    if (p[i] != '%') continue;
    if (i + 1 < p.size() && p[i + 1] == '%') {
      ++i;
      continue;
    }
    size_t j = i + 1;
    Conversion here;
    here.begin = i;
    if (j < p.size() && p[j] == '0') here.zero = true, ++j;
    while (j < p.size() && std::isdigit(static_cast<unsigned char>(p[j])) && here.width < 100)
      here.width = here.width * 10 + (p[j] - '0'), ++j;
    if (j >= p.size() || p[j] != 'd')
      throw InputError(p, "pattern", "only %d or %0Nd (e.g. %04d) may stand for the frame number");
    if (c.begin != std::string::npos) throw InputError(p, "pattern", "more than one frame-number conversion");
    here.end = j + 1;
    c = here;
    i = j;
  }
  return c;
}

std::string unescape(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    out += s[i];
    if (s[i] == '%' && i + 1 < s.size() && s[i + 1] == '%') ++i;
  }
  return out;
}

std::string cell(const json& v) {
  if (v.is_null()) return "n/a";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer() || v.is_number_unsigned()) return std::to_string(v.get<long long>());
  if (v.is_number()) {
    std::ostringstream s;
    s << std::setprecision(6) << v.get<double>();
    return s.str();
  }
  return v.dump();
}

void row(std::ostringstream& s, const std::string& name, const json& m) {
  std::string value, note;
  if (m.is_object() && m.contains("value")) {
    value = cell(m["value"]);
    if (m.value("unresolved", false)) note = "unresolved: reference too noisy";
  } else {
    value = cell(m);
  }
  s << "  " << std::left << std::setw(30) << name << std::setw(16) << value << note << '\n';
}

// The value at a dotted path ("flip.mean"), or nullptr.
const json* at_path(const json& root, std::string_view dotted) {
  const json* j = &root;
  while (!dotted.empty()) {
    const size_t dot = dotted.find('.');
    const std::string key(dotted.substr(0, dot));
    if (!j->is_object() || !j->contains(key)) return nullptr;
    j = &(*j)[key];
    dotted = dot == std::string_view::npos ? std::string_view() : dotted.substr(dot + 1);
  }
  return j;
}

}  // namespace

bool is_pattern(const std::string& path) { return parse_pattern(path).begin != std::string::npos; }

std::string path_from_output(const std::string& path, const std::filesystem::path& out_dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path from = fs::absolute(out_dir, ec).lexically_normal();
  const fs::path to = fs::absolute(path, ec).lexically_normal();
  if (ec) return path;
  const fs::path r = to.lexically_relative(from);
  return r.empty() ? to.string() : r.generic_string();
}

std::string frame_path(const std::string& pattern, int frame) {
  const Conversion c = parse_pattern(pattern);
  if (c.begin == std::string::npos) return unescape(pattern);
  std::string num = std::to_string(frame < 0 ? -frame : frame);
  if (c.zero && int(num.size()) < c.width - (frame < 0)) num.insert(0, size_t(c.width - (frame < 0)) - num.size(), '0');
  if (frame < 0) num.insert(0, "-");
  if (!c.zero && int(num.size()) < c.width) num.insert(0, size_t(c.width) - num.size(), ' ');
  return unescape(pattern.substr(0, c.begin)) + num + unescape(pattern.substr(c.end));
}

namespace {

// The files a metrics.json names (every "exr" and "png" entry, at any depth: the sequence's
// last frame carries its own maps and strip). An unreadable manifest names none.
void collect_outputs(const json& j, std::vector<std::string>& names) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      if ((key == "exr" || key == "png") && value.is_string()) names.push_back(value.get<std::string>());
      else collect_outputs(value, names);
    }
  } else if (j.is_array()) {
    for (const json& v : j) collect_outputs(v, names);
  }
}

std::vector<std::string> previous_outputs(const std::filesystem::path& manifest) {
  std::vector<std::string> names;
  if (!std::filesystem::is_regular_file(manifest)) return names;
  try {
    collect_outputs(read_json(manifest), names);
  } catch (const InputError&) {
  }
  return names;
}

// What both forms of score() write alike: what was done to the inputs beyond reading them,
// what makes the result doubtful, and the version.
void describe_treatment(json& result, bool sequence, bool ref_hdr, bool test_hdr, const ScoreRequest& req) {
  json& inputs = result["inputs"];
  if (req.test_layer && *req.test_layer != req.layer) inputs["test_layer"] = req.test_layer->empty() ? "beauty" : *req.test_layer;
  if (req.crop) inputs["crop"] = {req.crop->x, req.crop->y, req.crop->width, req.crop->height};
  if (!test_hdr) inputs["test_encoding"] = req.test_encoding == TestEncoding::Srgb ? "srgb" : "linear";
  if (req.display.active()) inputs["display"] = req.display.to_json();
  json warnings = json::array();
  if (ref_hdr && !test_hdr && req.display.curve == ToneCurve::None)
    warnings.push_back("the test is a low-dynamic-range image and the reference HDR, and no tone curve was given: "
                       "everything brighter than 1 in the reference (emitters, highlights) is clipped in the test and "
                       "counts as error; give the engine's tone curve and exposure (--tonemap, --exposure) or score a "
                       "linear EXR of its lighting buffer (docs/own-engine.md)");
  if (result.contains(sequence ? "last_frame" : "metrics")) {
    const json& found = sequence ? result["last_frame"] : result;
    for (const auto& w : found.value("warnings", json::array())) warnings.push_back(w);
    if (sequence && result["last_frame"].contains("warnings")) result["last_frame"].erase("warnings");
  }
  result["warnings"] = warnings;
  result["giq_version"] = giq::version();
  result["schema_version"] = kMetricsSchemaVersion;
  result["definitions"] = "docs/metrics.md";
}

}  // namespace

json score(const ScoreRequest& request) {
  // Every file lands in a locked staging folder first and is published as one set
  // (giq/base/staged_folder.h), so --out never mixes two runs.
  StagedFolder folder(request.out_dir, "metrics.json");
  ScoreRequest req = request;
  req.out_dir = folder.staging();
  json result;
  const bool sequence = req.frames.has_value() || is_pattern(req.test);
  if (sequence) {
    if (!req.frames) throw InputError(req.test, "--frames", "a frame pattern needs --frames A:B");
    if (!is_pattern(req.test))
      throw InputError(req.test, "--test", "with --frames the technique must be a pattern such as tech_%04d.exr");
    if (req.frames->first > req.frames->second)
      throw InputError("", "--frames",
                       std::to_string(req.frames->first) + ":" + std::to_string(req.frames->second) +
                           " is empty; expected A:B with A <= B");
    detail::Frames frames;
    frames.first = req.frames->first, frames.last = req.frames->second;
    frames.per_frame_reference = is_pattern(req.reference);
    frames.reference_name = [&](int f) { return frame_path(req.reference, f); };
    frames.test_name = [&](int f) { return frame_path(req.test, f); };
    frames.reference = [&](int f) { return detail::read_input(frame_path(req.reference, f), detail::Side::Reference, req); };
    frames.test = [&](int f) { return detail::read_input(frame_path(req.test, f), detail::Side::Test, req); };
    frames.reference_label = req.reference, frames.test_label = req.test;
    frames.hdr = detail::compares_hdr(frame_path(req.reference, frames.first), frame_path(req.test, frames.first), req);
    result = detail::score_sequence(frames, req);
  } else {
    if (is_pattern(req.reference))
      throw InputError(req.reference, "--ref", "a reference pattern needs a technique pattern and --frames");
    const image::Image ref = detail::read_input(req.reference, detail::Side::Reference, req);
    const image::Image test = detail::read_input(req.test, detail::Side::Test, req);
    result = detail::score_image(ref, req.reference, test, req.test, detail::compares_hdr(req.reference, req.test, req), req);
  }
  const std::string first_test = sequence ? frame_path(req.test, req.frames->first) : req.test;
  const std::string first_ref = is_pattern(req.reference) ? frame_path(req.reference, req.frames->first) : req.reference;
  describe_treatment(result, sequence, image::is_exr_file(first_ref), image::is_exr_file(first_test), req);
  // Paths relative to metrics.json's folder, so that the folder can move with its inputs and
  // be read from any working directory (giq report).
  json& inputs = result["inputs"];
  const auto relative = [&](const std::string& p) { return path_from_output(p, request.out_dir); };
  inputs["reference"] = relative(req.reference);
  inputs["test"] = relative(req.test);
  if (!req.scene.empty()) inputs["scene"] = relative(req.scene);
  if (req.frame_ms) {
    // "file:key" (gate::FrameTime::key): the file part is a path.
    const size_t colon = req.timings.rfind(':');
    inputs["frame_ms"] = *req.frame_ms;
    inputs["timings"] = colon == std::string::npos ? relative(req.timings)
                                                   : relative(req.timings.substr(0, colon)) + req.timings.substr(colon);
  }
  write_file_atomically(req.out_dir / "metrics.json", result.dump(2) + "\n");
  folder.publish(previous_outputs(request.out_dir / "metrics.json"));
  return result;
}

ScoreResult score(const ImageInputs& in, const ScoreRequest& request, bool keep_maps) {
  if (in.reference.empty() || in.test.empty())
    throw InputError(in.reference.empty() ? in.reference_name : in.test_name, "images", "none given");
  if (!in.sequence && (in.reference.size() != 1 || in.test.size() != 1))
    throw InputError(in.test_name, "images", "one reference and one test image expected outside a sequence");
  if (in.reference.size() != 1 && in.reference.size() != in.test.size())
    throw InputError(in.reference_name, "frames",
                     std::to_string(in.reference.size()) + " reference frames for " + std::to_string(in.test.size()) +
                         " test frames; expected one reference (a static scene) or one per test frame");
  std::optional<StagedFolder> folder;
  ScoreRequest req = request;
  req.write_maps = request.write_maps && !request.out_dir.empty();
  if (!request.out_dir.empty()) {
    folder.emplace(request.out_dir, "metrics.json");
    req.out_dir = folder->staging();
  }
  const size_t n = in.test.size();
  const bool per_frame_ref = in.reference.size() > 1 || (in.sequence && n == 1);
  auto name = [&](const std::string& base, size_t i) { return in.sequence ? base + "[" + std::to_string(i) + "]" : base; };
  auto ref_name = [&](int f) { return per_frame_ref ? name(in.reference_name, size_t(f)) : in.reference_name; };
  auto ref = [&](int f) {
    return detail::prepare_input(in.reference[per_frame_ref ? size_t(f) : 0], ref_name(f), in.reference_hdr,
                                 detail::Side::Reference, req);
  };
  auto test = [&](int f) {
    return detail::prepare_input(in.test[size_t(f)], name(in.test_name, size_t(f)), in.test_hdr, detail::Side::Test, req);
  };
  const bool hdr = in.reference_hdr && in.test_hdr && req.display.curve == ToneCurve::None;
  ScoreResult out;
  std::vector<Map>* kept = keep_maps ? &out.maps : nullptr;
  if (in.sequence) {
    detail::Frames frames;
    frames.first = 0, frames.last = int(n) - 1;
    frames.per_frame_reference = per_frame_ref;
    frames.hdr = hdr;
    frames.reference = ref, frames.test = test;
    frames.reference_name = ref_name;
    frames.test_name = [&](int f) { return name(in.test_name, size_t(f)); };
    frames.reference_label = in.reference_name, frames.test_label = in.test_name;
    out.metrics = detail::score_sequence(frames, req, kept);
  } else {
    out.metrics = detail::score_image(ref(0), in.reference_name, test(0), in.test_name, hdr, req, kept);
  }
  describe_treatment(out.metrics, in.sequence, in.reference_hdr, in.test_hdr, req);
  json& inputs = out.metrics["inputs"];
  if (!req.scene.empty()) inputs["scene"] = req.scene;
  if (req.frame_ms) inputs["frame_ms"] = *req.frame_ms, inputs["timings"] = req.timings;
  if (folder) {
    write_file_atomically(req.out_dir / "metrics.json", out.metrics.dump(2) + "\n");
    folder->publish(previous_outputs(request.out_dir / "metrics.json"));
  }
  return out;
}

std::string format_table(const json& j) {
  std::ostringstream s;
  const json& in = j.at("inputs");
  s << "giq score  " << in.value("test", "") << "  vs  " << in.value("reference", "") << "  [layer "
    << in.value("layer", "beauty") << ", " << in.value("dynamic_range", "") << "]\n";
  // A row for each catalogue metric of `scope` present in `m`, in the catalogue's order.
  auto rows = [&](const json& m, Scope scope) {
    for (const MetricInfo& info : kMetricCatalogue) {
      if (info.scope != scope) continue;
      for (size_t i = 0; i < info.paths.size() && !info.paths[i].empty(); ++i)
        if (const json* v = at_path(m, info.paths[i]))
          row(s, std::string(info.path_labels[i].empty() ? info.label : info.path_labels[i]), *v);
    }
  };
  if (j.contains("sequence")) {
    const json& q = j["sequence"];
    s << " sequence (" << cell(q["frames"]) << " frames)\n";
    rows(q, Scope::Sequence);
    s << " last frame\n";
    rows(j["last_frame"]["metrics"], Scope::Image);
  } else {
    rows(j["metrics"], Scope::Image);
  }
  return s.str();
}

}  // namespace giq::metrics
