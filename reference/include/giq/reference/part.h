#pragma once
// One render spread over processes or machines: `giq reference --shard K/N` renders a
// deterministic share of the work units into a part file, and `giq reference merge` joins the
// N parts into exactly the EXR files a single process would have written (docs/reference.md,
// "Shards").
//
// A work unit is one frame's tile of kUnitSize x kUnitSize pixels, numbered frame-major
// (u = (frame - first) x tiles per frame + tile, tiles row-major); shard K of N renders the
// units with u mod N = K - 1, so neighbouring tiles, which cost alike, go to different shards.
// Every pixel accumulates its samples in index order whichever process renders it (film.h),
// so a merged pixel has the bits of a single-process render. Units never split a pixel's
// samples: two processes' partial sums would enter its Welford updates in another order and
// change its last bits.
//
// The same format holds the checkpoint of a render across MPI ranks (distributed_render.h):
// shard 1/1, tiles whose pixels may have fewer samples than spp, and the frames already
// written.
//
// Format (native byte order, like checkpoints: every machine of one render runs the same
// build): the magic "giq-reference-part 2\n", the render's identity and metadata, the
// settings and every frame's camera field by field, then per frame the units' tiles
// (accumulators and first-hit layers as stored in memory), the frames written, and a 64-bit
// FNV-1a hash of everything before it.

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "giq/reference/film.h"
#include "giq/reference/renderer.h"
#include "giq/scenes/camera.h"

namespace giq::reference {

inline constexpr int kUnitSize = 64;

struct Shard {
  uint32_t index = 1;  // K, 1-based
  uint32_t count = 1;  // N
};
// "K/N" with 1 <= K <= N <= 1000000; throws InputError (field --shard) otherwise.
Shard parse_shard(const std::string& text);

// The units of a render of frames first..last at width x height.
struct WorkUnits {
  int first_frame = 0, last_frame = 0, width = 0, height = 0;
  struct Rect {
    int x0, y0, x1, y1;
    size_t pixels() const { return size_t(x1 - x0) * size_t(y1 - y0); }
  };
  Rect rect(uint32_t tile) const {
    const int x0 = int(tile % uint32_t(tiles_x())) * kUnitSize, y0 = int(tile / uint32_t(tiles_x())) * kUnitSize;
    return {x0, y0, std::min(x0 + kUnitSize, width), std::min(y0 + kUnitSize, height)};
  }
  uint64_t count() const { return uint64_t(last_frame - first_frame + 1) * uint64_t(tiles_per_frame()); }
  int tiles_x() const { return (width + kUnitSize - 1) / kUnitSize; }
  int tiles_y() const { return (height + kUnitSize - 1) / kUnitSize; }
  int tiles_per_frame() const { return tiles_x() * tiles_y(); }
  uint64_t unit(int frame, int tile) const { return uint64_t(frame - first_frame) * uint64_t(tiles_per_frame()) + uint64_t(tile); }
  static bool owned(uint64_t unit, Shard s) { return unit % s.count == s.index - 1; }
};

// One frame of a part: the camera its header records and the tiles the shard rendered.
struct PartFrame {
  int frame = 0;
  scenes::Camera camera;
  std::vector<uint32_t> tiles;             // ascending
  std::vector<PixelAccumulator> pixels;    // the tiles' pixels, tile after tile, rows within
  std::vector<PixelAux> aux;
};

struct Part {
  // What every part of one render shares (scene hash, view, camera as given, frames, spp,
  // settings): parts that differ in it are of different renders.
  std::string identity;
  std::string scene, scene_hash, view, camera_given;  // the EXR header's
  RenderSettings settings;                             // threads is not stored (never changes the image)
  uint32_t spp = 0;
  int first_frame = 0, last_frame = 0;
  Shard shard;
  std::vector<PartFrame> frames;  // the frames the shard has units in, ascending
  std::vector<int> written;       // a checkpoint's frames already written, ascending
};

// A tile's pixels in the layout of parts, checkpoints and MPI messages (rows top to bottom,
// each left to right): appended to pixels/aux, or copied back into the film from `pixels` and
// `aux` (rect(tile).pixels() of each).
void copy_tile_out(const Film& film, const WorkUnits& units, uint32_t tile, std::vector<PixelAccumulator>& pixels,
                   std::vector<PixelAux>& aux);
void copy_tile_in(Film& film, const WorkUnits& units, uint32_t tile, const PixelAccumulator* pixels, const PixelAux* aux);

// The tiles of `film` the shard owns in `frame`, copied into a PartFrame.
PartFrame part_frame(const Film& film, int frame, const scenes::Camera& camera, const WorkUnits& units, Shard shard);

// Written atomically. read_part throws InputError for a file that is not a part, is corrupt
// (checksum) or is inconsistent (tiles outside the image, sizes that do not match, pixels
// with other than spp samples; up to spp in a checkpoint).
void write_part(const std::filesystem::path& path, const Part& part);
enum class PartUse { Shard, Checkpoint };
Part read_part(const std::filesystem::path& path, PartUse use = PartUse::Shard);

struct MergedFrame {
  int frame = 0;
  scenes::Camera camera;
  Film film;
};
// The films of every frame from the N parts of one render, in frame order. Throws InputError
// (exit 2, one line) for parts of different renders, a shard given twice, missing shards
// (named) or a unit no part holds; `files` names the parts in messages.
std::vector<MergedFrame> merge_parts(const std::vector<Part>& parts, const std::vector<std::string>& files);

}  // namespace giq::reference
