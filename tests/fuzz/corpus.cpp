// giq-fuzz-corpus OUT: the seed corpus of every harness, from the project's own test inputs
// and from files written here with every codec and layout the readers meet:
//   OUT/gltf        the built-in scenes and tests/data/scenes, hostile ones included
//   OUT/exr         small EXRs: every compression, half/float/uint, multi-part, tiled
//   OUT/gate_config golden/gate.json and tests/data/gate
//   OUT/checkpoint  checkpoints of small films, with and without their checksum
//   OUT/part        the two parts of a small sharded render, with and without their checksum

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfTiledOutputFile.h>
#include <half.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz_input.h"
#include "giq/image/io.h"
#include "giq/reference/checkpoint.h"
#include "giq/reference/part.h"

namespace fs = std::filesystem;

namespace {

// Seeds above this size slow every mutation down; the readers' paths are the same on small
// files.
constexpr uintmax_t kMaxSeedBytes = 256 * 1024;

void copy_seeds(const fs::path& from, const fs::path& to, const std::vector<std::string>& extensions) {
  for (const auto& e : fs::recursive_directory_iterator(from)) {
    if (!e.is_regular_file() || e.file_size() > kMaxSeedBytes) continue;
    for (const std::string& ext : extensions)
      if (e.path().extension() == ext) {
        const std::string name = fs::relative(e.path(), from).string();
        std::string flat;
        for (char c : name) flat += (c == '/' || c == ' ') ? '_' : c;
        fs::copy_file(e.path(), to / flat, fs::copy_options::overwrite_existing);
      }
  }
}

void exr_seeds(const fs::path& to) {
  using giq::image::ExrOptions;
  giq::image::Image im(5, 3);
  for (const char* c : {"R", "G", "B", "indirect.R", "indirect.G", "indirect.B", "objectId"}) {
    float* p = im.add_channel(c);
    for (size_t i = 0; i < im.pixel_count(); ++i) p[i] = float(i) * 0.37f;
  }
  im.metadata["giq:view"] = "front";
  for (auto [name, c] : {std::pair{"none", ExrOptions::Compression::None}, std::pair{"zip", ExrOptions::Compression::Zip},
                         std::pair{"piz", ExrOptions::Compression::Piz}}) {
    ExrOptions o;
    o.compression = c;
    giq::image::write_exr(im, to / (std::string("layers_") + name + ".exr"), o);
    o.half_channels = {"R", "G", "B"};
    giq::image::write_exr(im, to / (std::string("half_") + name + ".exr"), o);
  }
  // Codecs giq never writes but other renderers do, one scanline file each.
  const int w = 8, h = 8;
  std::vector<Imath::half> rgb(size_t(w) * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = Imath::half(float(i % 17) * 0.25f);
  std::vector<uint32_t> ids(size_t(w) * h, 7u);
  auto frame = [&](Imf::FrameBuffer& fb) {
    for (int c = 0; c < 3; ++c)
      fb.insert(std::string(1, "RGB"[c]), Imf::Slice(Imf::HALF, (char*)(rgb.data() + c), 3 * sizeof(Imath::half),
                                                     3 * sizeof(Imath::half) * w));
    fb.insert("objectId", Imf::Slice(Imf::UINT, (char*)ids.data(), sizeof(uint32_t), sizeof(uint32_t) * w));
  };
  auto header = [&](Imf::Compression c) {
    Imf::Header hd(w, h);
    hd.compression() = c;
    for (const char* n : {"R", "G", "B"}) hd.channels().insert(n, Imf::Channel(Imf::HALF));
    hd.channels().insert("objectId", Imf::Channel(Imf::UINT));
    return hd;
  };
  const std::pair<const char*, Imf::Compression> codecs[] = {
      {"rle", Imf::RLE_COMPRESSION},     {"zips", Imf::ZIPS_COMPRESSION}, {"pxr24", Imf::PXR24_COMPRESSION},
      {"b44", Imf::B44_COMPRESSION},     {"b44a", Imf::B44A_COMPRESSION}, {"dwaa", Imf::DWAA_COMPRESSION},
      {"dwab", Imf::DWAB_COMPRESSION}};
  for (auto [name, c] : codecs) {
    Imf::Header hd = header(c);
    Imf::OutputFile out((to / (std::string("codec_") + name + ".exr")).c_str(), hd);
    Imf::FrameBuffer fb;
    frame(fb);
    out.setFrameBuffer(fb);
    out.writePixels(h);
  }
  {  // Two parts, one layer each, as some compositors write.
    std::vector<Imf::Header> parts{header(Imf::ZIP_COMPRESSION), header(Imf::PIZ_COMPRESSION)};
    parts[0].setName("beauty");
    parts[1].setName("indirect");
    for (auto& p : parts) p.setType(Imf::SCANLINEIMAGE);
    Imf::MultiPartOutputFile out((to / "multipart.exr").c_str(), parts.data(), int(parts.size()));
    for (int i = 0; i < 2; ++i) {
      Imf::OutputPart part(out, i);
      Imf::FrameBuffer fb;
      frame(fb);
      part.setFrameBuffer(fb);
      part.writePixels(h);
    }
  }
  {  // Tiled, with mipmaps.
    Imf::Header hd = header(Imf::ZIP_COMPRESSION);
    hd.setTileDescription(Imf::TileDescription(4, 4, Imf::MIPMAP_LEVELS));
    Imf::TiledOutputFile out((to / "tiled_mipmap.exr").c_str(), hd);
    for (int level = 0; level < out.numLevels(); ++level) {
      Imf::FrameBuffer fb;
      frame(fb);
      out.setFrameBuffer(fb);
      out.writeTiles(0, out.numXTiles(level) - 1, 0, out.numYTiles(level) - 1, level);
    }
  }
}

void checkpoint_seeds(const fs::path& to) {
  for (auto [w, h] : {std::pair{1, 1}, std::pair{2, 3}}) {
    giq::reference::Film film(w, h);
    const std::string name = "film_" + std::to_string(w) + "x" + std::to_string(h);
    giq::reference::write_checkpoint(to / (name + ".ckpt"), film, giq::fuzz::kCheckpointIdentity, 12.5);
    // The harness's other form: 0x01, then the file without its checksum.
    std::ifstream in(to / (name + ".ckpt"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    bytes.resize(bytes.size() - sizeof(uint64_t));
    std::ofstream(to / (name + "_unsummed.ckpt"), std::ios::binary) << '\x01' << bytes;
  }
}

// Parts of a 65 x 3 render of two frames (2 units a frame: 64 x 3 and 1 x 3 pixels) cut in two
// shards; small, so that the harness runs many inputs a second.
void part_seeds(const fs::path& to) {
  namespace ref = giq::reference;
  for (uint32_t k = 1; k <= 2; ++k) {
    ref::Part part;
    part.identity = "scene 0 view front camera '' frames 3:4 spp 2 settings {}";
    part.scene = "scene.gltf", part.scene_hash = "0", part.view = "front";
    part.settings.width = 65, part.settings.height = 3;
    part.spp = 2, part.first_frame = 3, part.last_frame = 4, part.shard = {k, 2};
    const ref::WorkUnits units{3, 4, 65, 3};
    for (int f = 3; f <= 4; ++f) {
      ref::Film film(65, 3, 32);
      for (ref::PixelAccumulator& p : film.pixels) p.samples = 2;
      part.frames.push_back(ref::part_frame(film, f, giq::scenes::Camera{}, units, part.shard));
    }
    const std::string name = "shard_" + std::to_string(k) + "_of_2";
    ref::write_part(to / (name + ".part"), part);
    std::ifstream in(to / (name + ".part"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    bytes.resize(bytes.size() - sizeof(uint64_t));
    std::ofstream(to / (name + "_unsummed.part"), std::ios::binary) << '\x01' << bytes;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: giq-fuzz-corpus OUT\n");
    return 2;
  }
  const fs::path out = argv[1], source = GIQ_SOURCE_DIR;
  for (const char* h : {"gltf", "exr", "gate_config", "checkpoint", "part"}) fs::create_directories(out / h);
  copy_seeds(source / "scenes", out / "gltf", {".gltf", ".glb"});
  copy_seeds(source / "tests/data/scenes", out / "gltf", {".gltf", ".glb"});
  exr_seeds(out / "exr");
  fs::copy_file(source / "golden/gate.json", out / "gate_config/golden_gate.json", fs::copy_options::overwrite_existing);
  copy_seeds(source / "tests/data/gate", out / "gate_config", {".json"});
  checkpoint_seeds(out / "checkpoint");
  part_seeds(out / "part");
  return 0;
}
