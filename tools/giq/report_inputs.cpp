#include "report_inputs.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "giq/base/error.h"
#include "giq/base/json.h"
#include "giq/gate/escape.h"
#include "giq/image/io.h"
#include "giq/metrics/catalogue.h"
#include "output_guard.h"

namespace giq::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string data_uri(const std::string& mime, const std::string& bytes) {
  return "data:" + mime + ";base64," + gate::base64(bytes);
}

// An EXR (or any image) tone-mapped to a PNG data URI; giq::image writes files, so the PNG
// goes through a temporary file.
std::string png_uri(const image::Image& img, const std::string& layer, float exposure) {
  static int counter = 0;
  const fs::path tmp = fs::temp_directory_path() / ("giq_report_" + std::to_string(::getpid()) +
                                                    "_" + std::to_string(counter++) + ".png");
  image::PngOptions o;
  o.layer = layer;
  o.exposure = exposure;
  image::write_png(img, tmp, o);
  std::string bytes = slurp(tmp);
  std::error_code ec;
  fs::remove(tmp, ec);
  return data_uri("image/png", bytes);
}

// A path written into metrics.json: as given (relative to where giq score ran) when it
// exists, else relative to the metrics.json folder.
// An input path of a metrics.json in folder `beside`: relative to that folder from schema
// version 2 on (metrics/score.h), as typed before, where the working directory came first.
fs::path locate(const std::string& p, const fs::path& beside, int schema_version) {
  if (schema_version >= 2) return fs::path(p).is_absolute() ? fs::path(p) : beside / p;
  if (fs::exists(p)) return p;
  return beside / p;
}

std::string frame_file(const std::string& pattern, int frame) {
  char buf[4096];
  std::snprintf(buf, sizeof buf, pattern.c_str(), frame);
  return buf;
}

std::string value_text(const json& m) {
  const json& v = m.is_object() ? m.value("value", json(nullptr)) : m;
  std::string s;
  if (v.is_number()) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v.get<double>());
    s = buf;
  } else if (v.is_string()) {
    s = v.get<std::string>();
  } else {
    s = "n/a";
  }
  if (m.is_object() && m.value("unresolved", false))
    s += " (unresolved: below the reference's noise)";
  return s;
}

// A row for each per-image metric of the catalogue present in `m`, with the catalogue's labels.
void add_metric_rows(Comparison& c, const json& m, const std::string& prefix) {
  for (const metrics::MetricInfo& info : metrics::kMetricCatalogue) {
    if (info.scope != metrics::Scope::Image) continue;
    for (size_t i = 0; i < info.paths.size() && !info.paths[i].empty(); ++i) {
      const json* v = &m;
      for (std::string_view rest = info.paths[i]; v && !rest.empty();) {
        const size_t dot = rest.find('.');
        const std::string key(rest.substr(0, dot));
        v = v->is_object() && v->contains(key) ? &(*v)[key] : nullptr;
        rest = dot == std::string_view::npos ? std::string_view() : rest.substr(dot + 1);
      }
      if (v)
        c.metrics.emplace_back(prefix + std::string(info.path_labels[i].empty() ? info.label : info.path_labels[i]),
                               value_text(*v));
    }
  }
}

// The error maps are embedded byte for byte, so only PNG files under the report's folder are:
// a metrics.json could otherwise name any file on the machine (an absolute path, "../") and
// carry it into a page that is shared.
void add_maps(Comparison& c, const json& maps, const fs::path& dir, const fs::path& root, const fs::path& file) {
  if (!maps.is_object()) return;
  for (const auto& [name, m] : maps.items()) {
    const fs::path png = dir / m.value("png", "");
    if (!m.contains("png") || !fs::exists(png)) continue;
    if (!path_inside(png, root))
      throw InputError(file.string(), "maps." + name + ".png",
                       "'" + png.string() + "' is outside " + root.string() + "; the report reads only files under its folder");
    const std::string bytes = slurp(png);
    if (bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0)
      throw InputError(file.string(), "maps." + name + ".png", "'" + png.string() + "' is not a PNG image");
    Picture p;
    p.title = name + " (" + m.value("definition", "") + ")";
    p.data_uri = data_uri("image/png", bytes);
    ColourScale s;
    s.colormap = m.value("colormap", "magma");
    if (m.contains("range") && m["range"].is_array() && m["range"].size() == 2 &&
        m["range"][0].is_number() && m["range"][1].is_number())
      s.lo = m["range"][0], s.hi = m["range"][1];
    s.unit = m.value("unit", "");
    s.rule = m.value("range_rule", "");
    p.scale = s;
    c.maps.push_back(p);
  }
}

// The readout's values: the scored layer of both images and every error map's EXR (under the
// report's folder, as add_maps requires of the PNGs), when the images are small enough.
void add_readout(Comparison& c, const image::Image& r, const image::Image& t, const std::string& layer, const json& maps,
                 const fs::path& dir, const fs::path& root) {
  if (r.pixel_count() > kReadoutPixels || r.width() != t.width() || r.height() != t.height()) return;
  if (!r.has_layer(layer) || !t.has_layer(layer)) return;
  auto channel = [&](const image::Image& img, const std::string& name) {
    const float* v = img.channel(name);
    return std::vector<float>(v, v + img.pixel_count());
  };
  Comparison::Readout& o = c.readout;
  o.width = r.width(), o.height = r.height();
  const auto rc = r.layer_channels(layer), tc = t.layer_channels(layer);
  const char* const suffix[3] = {" R", " G", " B"};
  for (size_t k = 0; k < 3; ++k) o.channels.emplace_back(std::string("reference") + suffix[k], channel(r, rc[k]));
  for (size_t k = 0; k < 3; ++k) o.channels.emplace_back(c.technique + suffix[k], channel(t, tc[k]));
  if (!maps.is_object()) return;
  for (const auto& [name, m] : maps.items()) {
    const fs::path exr = dir / m.value("exr", "");
    if (!m.contains("exr") || !fs::exists(exr) || !path_inside(exr, root)) continue;
    try {
      const image::Image e = image::read_image(exr);
      if (e.width() == o.width && e.height() == o.height && !e.channel_names().empty())
        o.channels.emplace_back(name, channel(e, e.channel_names().front()));
    } catch (const InputError&) {
      // A map that cannot be read is left out of the readout; its picture still shows.
    }
  }
}

Comparison comparison(const fs::path& file, const fs::path& root, int max_frames) {
  const json j = read_json(file);
  const fs::path dir = file.parent_path();
  const json& in = j.at("inputs");
  Comparison c;
  c.source = fs::relative(file, root).generic_string();
  c.layer = in.value("layer", "beauty");
  c.label = fs::relative(dir, root).generic_string();
  // A gate case keeps its score in cases/<name>/score: the case name is the better label.
  if (dir.filename() == "score" && dir.parent_path().parent_path().filename() == "cases")
    c.label = dir.parent_path().filename().string();
  const std::string layer = c.layer == "beauty" ? "" : c.layer;
  const float exposure = j.contains("strip") ? j["strip"].value("exposure", 0.0f) : 0.0f;
  const std::string ref = in.at("reference"), test = in.at("test");
  const bool sequence = j.contains("sequence") && in.contains("frames");
  int last = 0;
  if (sequence) c.first_frame = in["frames"][0], last = in["frames"][1];
  const int schema = j.value("schema_version", 1);
  auto ref_path = [&](int f) {
    return locate(ref.find('%') != std::string::npos ? frame_file(ref, f) : ref, dir, schema);
  };
  auto test_path = [&](int f) {
    return locate(test.find('%') != std::string::npos ? frame_file(test, f) : test, dir, schema);
  };

  const image::Image r = image::read_image(ref_path(last));
  const image::Image t = image::read_image(test_path(last));
  c.scene = in.value("scene", "");
  if (c.scene.empty() && r.metadata.count("giq.scene")) c.scene = r.metadata.at("giq.scene");
  if (c.scene.empty() && j.contains("inputs") && j["inputs"].contains("scene"))
    c.scene = j["inputs"]["scene"];
  if (c.scene.empty()) c.scene = "(scene not recorded)";
  c.technique = t.metadata.count("giq.technique")
                    ? t.metadata.at("giq.technique")
                    : test_path(last).parent_path().filename().string();
  c.panes.push_back(
      {"reference" + std::string(sequence ? " (frame " + std::to_string(last) + ")" : ""),
       png_uri(r, layer, exposure),
       {}});
  c.panes.push_back({c.technique + (sequence ? " (frame " + std::to_string(last) + ")" : ""),
                     png_uri(t, layer, exposure),
                     {}});

  if (sequence) {
    const int n = last - c.first_frame + 1;
    const int step = std::max(1, (n + max_frames - 1) / std::max(1, max_frames));
    for (int f = c.first_frame; f <= last; f += step) {
      c.reference_frames.push_back(png_uri(image::read_image(ref_path(f)), layer, exposure));
      c.technique_frames.push_back(png_uri(image::read_image(test_path(f)), layer, exposure));
    }
    const json& q = j["sequence"];
    for (const char* k :
         {"flicker", "temporal_flip", "bias2", "variance", "lag90_frames", "lag90_ms"})
      if (q.contains(k)) c.metrics.emplace_back(k, value_text(q[k]));
    if (j.contains("last_frame")) {
      if (j["last_frame"].contains("metrics"))
        add_metric_rows(c, j["last_frame"]["metrics"], "last frame: ");
      if (j["last_frame"].contains("maps")) add_maps(c, j["last_frame"]["maps"], dir, root, file);
    }
  } else if (j.contains("metrics")) {
    add_metric_rows(c, j["metrics"], "");
  }
  if (j.contains("maps")) add_maps(c, j["maps"], dir, root, file);
  add_readout(c, r, t, layer, sequence && j.contains("last_frame") ? j["last_frame"].value("maps", json()) : j.value("maps", json()),
              dir, root);
  for (const metrics::MetricInfo& info : metrics::kMetricCatalogue)
    if (info.headline && info.scope != metrics::Scope::Timing)
      if (const auto v = gate::find_metric(j, std::string(info.name)); v && v->value)
        c.headline.emplace_back(std::string(info.name), *v);
  if (in.contains("frame_ms") && in["frame_ms"].is_number()) c.gpu_ms = in["frame_ms"].get<double>();
  for (const json& w : j.value("warnings", json::array()))
    if (w.is_string()) c.warnings.push_back(w.get<std::string>());
  return c;
}

}  // namespace

ReportInputs scan_report_inputs(const fs::path& dir, int max_frames) {
  if (!fs::is_directory(dir))
    throw InputError(dir.string(), "DIR",
                     "not a folder; expected giq gate, score or sweep outputs");
  ReportInputs r;
  r.dir = dir;
  std::vector<fs::path> files;
  for (const auto& e :
       fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  // The scores of a sweep's settings are summarised by its table and plot, not shown one by one.
  std::vector<fs::path> sweep_dirs;
  for (const fs::path& f : files)
    if (f.filename() == "sweep.json" || f.filename() == "convergence.json")
      sweep_dirs.push_back(f.parent_path());
  auto in_sweep = [&](const fs::path& f) {
    return std::any_of(sweep_dirs.begin(), sweep_dirs.end(), [&](const fs::path& d) {
      const std::string rel = fs::relative(f, d).generic_string();
      return !rel.empty() && rel.rfind("..", 0) != 0;
    });
  };
  for (const fs::path& f : files) {
    const std::string name = f.filename().string();
    try {
      if (name == "metrics.json" && in_sweep(f)) {
        continue;
      } else if (name == "metrics.json") {
        r.comparisons.push_back(comparison(f, dir, max_frames));
      } else if (name == "gate.json") {
        json gate = read_json(f);
        if (!gate.is_object() || !gate.contains("outcomes") || !gate["outcomes"].is_array())
          throw InputError(f.string(), "outcomes", "missing; expected the object giq gate writes");
        r.gate = std::move(gate);
      } else if (name == "sweep.json") {
        r.sweeps.push_back({fs::relative(f, dir).generic_string(), read_json(f)});
      } else if (f.extension() == ".svg") {
        r.plots.push_back(
            {fs::relative(f, dir).generic_string(), data_uri("image/svg+xml", slurp(f)), {}});
      }
    } catch (const std::exception& e) {
      r.warnings.push_back(fs::relative(f, dir).generic_string() + ": " + e.what());
    }
  }
  std::stable_sort(r.comparisons.begin(), r.comparisons.end(),
                   [](const Comparison& a, const Comparison& b) { return a.scene < b.scene; });
  if (r.comparisons.empty() && !r.gate && r.sweeps.empty() && r.plots.empty())
    throw InputError(dir.string(), "DIR",
                     "holds no metrics.json, gate.json, sweep.json or plot" +
                         (r.warnings.empty() ? std::string()
                                             : " that could be read (" + r.warnings.front() + ")"));
  return r;
}

}  // namespace giq::cli
