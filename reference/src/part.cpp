#include "giq/reference/part.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <type_traits>

#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "giq/base/hash.h"
#include "binary_record.h"

namespace giq::reference {
namespace {

constexpr char kMagic[] = "giq-reference-part 2\n";
static_assert(std::is_trivially_copyable_v<PixelAccumulator> && std::is_trivially_copyable_v<PixelAux>);

void put_camera(std::string& out, const scenes::Camera& c) {
  for (const glm::vec3& v : {c.position, c.forward, c.up, c.right})
    for (int k = 0; k < 3; ++k) put(out, v[k]);
  for (float f : {c.yfov, c.ymag, c.znear, c.zfar}) put(out, f);
}
scenes::Camera get_camera(RecordReader& r) {
  scenes::Camera c;
  for (glm::vec3* v : {&c.position, &c.forward, &c.up, &c.right})
    for (int k = 0; k < 3; ++k) (*v)[k] = r.get<float>();
  for (float* f : {&c.yfov, &c.ymag, &c.znear, &c.zfar}) *f = r.get<float>();
  return c;
}

WorkUnits units_of(const Part& p) {
  return {p.first_frame, p.last_frame, p.settings.width, p.settings.height};
}

}  // namespace

Shard parse_shard(const std::string& text) {
  unsigned long k = 0, n = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lu/%lu%c", &k, &n, &tail) != 2 || k < 1 || n < 1 || k > n || n > 1000000 ||
      text.find_first_not_of("0123456789/") != std::string::npos)
    throw InputError("", "--shard", "'" + text + "'; expected K/N, this process's share K of N shares (1 <= K <= N), e.g. 3/8");
  return {uint32_t(k), uint32_t(n)};
}

void copy_tile_out(const Film& film, const WorkUnits& units, uint32_t tile, std::vector<PixelAccumulator>& pixels,
                   std::vector<PixelAux>& aux) {
  const WorkUnits::Rect r = units.rect(tile);
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const size_t i = size_t(y) * size_t(film.width) + size_t(x);
      pixels.push_back(film.pixels[i]);
      aux.push_back(film.aux[i]);
    }
}

void copy_tile_in(Film& film, const WorkUnits& units, uint32_t tile, const PixelAccumulator* pixels, const PixelAux* aux) {
  const WorkUnits::Rect r = units.rect(tile);
  size_t at = 0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x, ++at) {
      const size_t i = size_t(y) * size_t(film.width) + size_t(x);
      film.pixels[i] = pixels[at];
      film.aux[i] = aux[at];
    }
}

PartFrame part_frame(const Film& film, int frame, const scenes::Camera& camera, const WorkUnits& units, Shard shard) {
  PartFrame pf;
  pf.frame = frame;
  pf.camera = camera;
  for (int t = 0; t < units.tiles_per_frame(); ++t) {
    if (!WorkUnits::owned(units.unit(frame, t), shard)) continue;
    pf.tiles.push_back(uint32_t(t));
    copy_tile_out(film, units, uint32_t(t), pf.pixels, pf.aux);
  }
  return pf;
}

void write_part(const std::filesystem::path& path, const Part& p) {
  std::string out(kMagic);
  put_string(out, p.identity);
  for (const std::string* s : {&p.scene, &p.scene_hash, &p.view, &p.camera_given}) put_string(out, *s);
  const RenderSettings& s = p.settings;
  put(out, int32_t(s.width)), put(out, int32_t(s.height)), put(out, uint64_t(s.seed)), put(out, int32_t(s.max_bounces));
  put(out, uint8_t(s.estimator)), put(out, uint8_t(s.sampler)), put(out, uint32_t(s.sobol_block)), put(out, uint8_t(s.pixel_centre));
  put(out, p.spp), put(out, int32_t(p.first_frame)), put(out, int32_t(p.last_frame));
  put(out, p.shard.index), put(out, p.shard.count);
  put(out, uint32_t(p.frames.size()));
  for (const PartFrame& f : p.frames) {
    put(out, int32_t(f.frame));
    put_camera(out, f.camera);
    put(out, uint32_t(f.tiles.size()));
    for (uint32_t t : f.tiles) put(out, t);
    if (f.pixels.empty()) continue;  // a frame without tiles has no pixel data (and null data())
    out.append(reinterpret_cast<const char*>(f.pixels.data()), f.pixels.size() * sizeof(PixelAccumulator));
    out.append(reinterpret_cast<const char*>(f.aux.data()), f.aux.size() * sizeof(PixelAux));
  }
  put(out, uint32_t(p.written.size()));
  for (int f : p.written) put(out, int32_t(f));
  put(out, Hasher().add(out).value());
  write_file_atomically(path, out);
}

Part read_part(const std::filesystem::path& path, PartUse use) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "", "cannot open the file");
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t magic = sizeof(kMagic) - 1;
  if (data.size() < magic + sizeof(uint64_t) || data.compare(0, magic, kMagic) != 0)
    throw InputError(file, "part",
                     std::string(use == PartUse::Shard ? "not a part of a sharded reference render"
                                                       : "not a checkpoint of a reference render across MPI ranks") +
                         " (expected it to start with 'giq-reference-part 2')");
  const size_t end = data.size() - sizeof(uint64_t);
  uint64_t stored_hash;
  std::memcpy(&stored_hash, data.data() + end, sizeof(uint64_t));
  if (Hasher().add(data.data(), end).value() != stored_hash)
    throw InputError(file, "part",
                     std::string("checksum mismatch: the file is corrupt or incomplete; ") +
                         (use == PartUse::Shard ? "render this shard again" : "start again with --overwrite"));
  RecordReader r(data, end, file, "part", "the file is truncated");
  std::string skip(magic, '\0');
  r.bytes(skip.data(), magic);
  Part p;
  p.identity = r.string();
  for (std::string* s : {&p.scene, &p.scene_hash, &p.view, &p.camera_given}) *s = r.string();
  RenderSettings& s = p.settings;
  s.width = r.get<int32_t>(), s.height = r.get<int32_t>(), s.seed = r.get<uint64_t>(), s.max_bounces = r.get<int32_t>();
  const uint8_t estimator = r.get<uint8_t>(), sampler = r.get<uint8_t>();
  s.sobol_block = r.get<uint32_t>();
  const uint8_t centre = r.get<uint8_t>();
  if (s.width < 1 || s.height < 1 || s.width > 65536 || s.height > 65536)
    r.fail("image size " + std::to_string(s.width) + "x" + std::to_string(s.height) + " is invalid");
  if (estimator > uint8_t(Estimator::BsdfOnly) || sampler > uint8_t(Sampler::Independent) || centre > 1)
    r.fail("the settings hold values no giq writes");
  s.estimator = Estimator(estimator), s.sampler = Sampler(sampler), s.pixel_centre = centre != 0;
  p.spp = r.get<uint32_t>();
  p.first_frame = r.get<int32_t>(), p.last_frame = r.get<int32_t>();
  p.shard.index = r.get<uint32_t>(), p.shard.count = r.get<uint32_t>();
  if (p.first_frame < 0 || p.last_frame < p.first_frame || p.shard.index < 1 || p.shard.index > p.shard.count)
    r.fail("frames " + std::to_string(p.first_frame) + ":" + std::to_string(p.last_frame) + " or shard " +
           std::to_string(p.shard.index) + "/" + std::to_string(p.shard.count) + " are invalid");
  const WorkUnits units = units_of(p);
  const uint32_t frames = r.get<uint32_t>();
  if (uint64_t(frames) > uint64_t(p.last_frame - p.first_frame) + 1) r.fail("more frames than the render has");
  for (uint32_t i = 0; i < frames; ++i) {
    PartFrame f;
    f.frame = r.get<int32_t>();
    if (f.frame < p.first_frame || f.frame > p.last_frame || (!p.frames.empty() && f.frame <= p.frames.back().frame))
      r.fail("frame " + std::to_string(f.frame) + " is outside the render's frames or out of order");
    f.camera = get_camera(r);
    const uint32_t tiles = r.get<uint32_t>();
    if (tiles > uint32_t(units.tiles_per_frame())) r.fail("more tiles than a frame has");
    size_t pixels = 0;
    for (uint32_t k = 0; k < tiles; ++k) {
      const uint32_t t = r.get<uint32_t>();
      if (t >= uint32_t(units.tiles_per_frame()) || (!f.tiles.empty() && t <= f.tiles.back()) ||
          !WorkUnits::owned(units.unit(f.frame, int(t)), p.shard))
        r.fail("tile " + std::to_string(t) + " of frame " + std::to_string(f.frame) + " is not one of this shard's");
      f.tiles.push_back(t);
      pixels += units.rect(t).pixels();
    }
    // The declared size against the file before anything is allocated.
    if (pixels * (sizeof(PixelAccumulator) + sizeof(PixelAux)) > r.left()) r.fail("the file is truncated");
    f.pixels.resize(pixels);
    f.aux.resize(pixels);
    r.bytes(f.pixels.data(), pixels * sizeof(PixelAccumulator));
    r.bytes(f.aux.data(), pixels * sizeof(PixelAux));
    for (const PixelAccumulator& a : f.pixels)
      if (use == PartUse::Shard ? a.samples != p.spp : a.samples > p.spp)
        r.fail("a pixel of frame " + std::to_string(f.frame) + " has " + std::to_string(a.samples) +
               (use == PartUse::Shard ? " samples, not the render's " : " samples, more than the render's ") +
               std::to_string(p.spp));
    p.frames.push_back(std::move(f));
  }
  const uint32_t written = r.get<uint32_t>();
  if (uint64_t(written) > uint64_t(p.last_frame - p.first_frame) + 1) r.fail("more frames written than the render has");
  for (uint32_t i = 0; i < written; ++i) {
    const int f = r.get<int32_t>();
    if (f < p.first_frame || f > p.last_frame || (!p.written.empty() && f <= p.written.back()))
      r.fail("written frame " + std::to_string(f) + " is outside the render's frames or out of order");
    p.written.push_back(f);
  }
  if (r.left() != 0) r.fail(std::to_string(r.left()) + " bytes follow the last frame");
  return p;
}

std::vector<MergedFrame> merge_parts(const std::vector<Part>& parts, const std::vector<std::string>& files) {
  if (parts.empty()) throw InputError("", "parts", "none given; expected the N part files of one render");
  const Part& first = parts.front();
  std::map<uint32_t, size_t> by_shard;
  for (size_t i = 0; i < parts.size(); ++i) {
    const Part& p = parts[i];
    if (p.identity != first.identity)
      throw InputError(files[i], "part",
                       "belongs to another render than " + files[0] + ": it is '" + p.identity + "', that one '" +
                           first.identity + "'");
    if (p.shard.count != first.shard.count)
      throw InputError(files[i], "part", "is shard " + std::to_string(p.shard.index) + " of " + std::to_string(p.shard.count) +
                                             ", " + files[0] + " one of " + std::to_string(first.shard.count));
    if (const auto [it, fresh] = by_shard.emplace(p.shard.index, i); !fresh)
      throw InputError(files[i], "part", "shard " + std::to_string(p.shard.index) + "/" + std::to_string(p.shard.count) +
                                             " is given twice: also " + files[it->second]);
  }
  if (by_shard.size() != first.shard.count) {
    std::string missing;
    size_t n = 0;
    for (uint32_t k = 1; k <= first.shard.count; ++k)
      if (!by_shard.count(k) && n++ < 20) missing += (missing.empty() ? "" : ", ") + std::to_string(k);
    if (n > 20) missing += " and " + std::to_string(n - 20) + " more";
    throw InputError("", "parts", (n == 1 ? "shard " : "shards ") + missing + " of " + std::to_string(first.shard.count) +
                                      (n == 1 ? " is" : " are") + " missing: merge needs every part of the render");
  }
  const WorkUnits units = units_of(first);
  std::vector<MergedFrame> out;
  for (int frame = first.first_frame; frame <= first.last_frame; ++frame) {
    MergedFrame m;
    m.frame = frame;
    m.film = Film(units.width, units.height);
    std::vector<uint8_t> covered(size_t(units.tiles_per_frame()), 0);
    bool has_camera = false;
    for (const auto& [index, i] : by_shard) {  // shard order: a fixed order, whatever the files' order
      for (const PartFrame& f : parts[i].frames) {
        if (f.frame != frame) continue;
        if (!has_camera) m.camera = f.camera, has_camera = true;
        size_t at = 0;
        for (uint32_t t : f.tiles) {
          covered[t] = 1;
          copy_tile_in(m.film, units, t, f.pixels.data() + at, f.aux.data() + at);
          at += units.rect(t).pixels();
        }
      }
    }
    for (int t = 0; t < units.tiles_per_frame(); ++t)
      if (!covered[size_t(t)])
        throw InputError(files[by_shard.at(uint32_t(units.unit(frame, t) % first.shard.count) + 1)], "part",
                         "holds no tile " + std::to_string(t) + " of frame " + std::to_string(frame) + ", which is its share");
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace giq::reference
