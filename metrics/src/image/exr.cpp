// Multi-layer OpenEXR through the OpenEXR 3 C++ library (no OpenImageIO), so the real-time
// runner can write references and technique frames with a ~6 MB dependency footprint.

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputPart.h>
#include <ImfMultiPartInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfPartType.h>
#include <ImfThreading.h>

#include <half.h>

#include <algorithm>
#include <exception>
#include <fstream>
#include <map>
#include <mutex>
#include <thread>
#include <vector>
#include <set>

#include "declared_size.h"
#include "exr.h"
#include "giq/image/io.h"
#include "giq/base/atomic_file.h"
#include "giq/base/error.h"

namespace giq::image {
namespace fs = std::filesystem;

namespace {

// giq's header keys are snake_case ("giq.scene_hash", "giq.gpu_ms"); references written
// before the reference and the real-time module shared that style used camelCase for three
// of them. They are read under today's names, so older goldens and references stay readable.
std::string current_key(const std::string& key) {
  if (key == "giq.sceneHash") return "giq.scene_hash";
  if (key == "giq.renderTime") return "giq.render_time";
  if (key == "giq.nonFiniteSamples") return "giq.nonfinite_samples";
  return key;
}

Imf::Compression to_imf(ExrOptions::Compression c) {
  switch (c) {
    case ExrOptions::Compression::None: return Imf::NO_COMPRESSION;
    case ExrOptions::Compression::Zip: return Imf::ZIP_COMPRESSION;
    case ExrOptions::Compression::Piz: return Imf::PIZ_COMPRESSION;
  }
  return Imf::ZIP_COMPRESSION;
}

// OpenEXR compresses and decompresses chunks on its own thread pool, which is off (0 threads)
// unless asked for. It reserves two chunk buffers per thread for every part it opens
// (check_declared_sizes), so the pool is capped: four threads decode giq's images as fast as
// the disk delivers them, and what a file can make giq reserve does not grow with the core count.
constexpr int kExrThreads = 4;

void enable_threads() {
  static std::once_flag once;
  std::call_once(once, [] { Imf::setGlobalThreadCount(int(std::clamp(std::thread::hardware_concurrency(), 1u, unsigned(kExrThreads)))); });
}

// The largest ratio of pixel data (as stored: 2 bytes a half, 4 a float or uint) to
// compressed bytes each codec can reach; 0 for a codec this bound does not know.
double max_compression_ratio(Imf::Compression c) {
  switch (c) {
    case Imf::NO_COMPRESSION: return 1.0;
    case Imf::RLE_COMPRESSION: return 64.0;  // a run of 128 equal bytes in 2
    case Imf::ZIPS_COMPRESSION:
    case Imf::ZIP_COMPRESSION: return 1032.0;  // deflate's limit: 258 bytes in 2 bits
    case Imf::PXR24_COMPRESSION: return 1032.0 * 4.0 / 3.0;  // floats cut to 24 bits, then deflate
    // Huffman codes with run-length symbols (at most 255 repeats in at least 9 bits, about
    // 455:1); deflate's limit is the rounder bound.
    case Imf::PIZ_COMPRESSION: return 1032.0;
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION: return 32.0 / 3.0;  // a flat 4x4 block of halves in 3 bytes
    // An 8x8 DCT block down to its DC value and an end code (4 bytes for 128), then deflate;
    // twice that, as the lossless channels take other paths.
    case Imf::DWAA_COMPRESSION:
    case Imf::DWAB_COMPRESSION: return 64.0 * 1032.0;
    default: return 0.0;
  }
}

// Scan lines per chunk of each codec (OpenEXR file layout, "Compression"); 256, the most, for
// one this table does not know.
int lines_per_chunk(Imf::Compression c) {
  switch (c) {
    case Imf::NO_COMPRESSION:
    case Imf::RLE_COMPRESSION:
    case Imf::ZIPS_COMPRESSION: return 1;
    case Imf::ZIP_COMPRESSION:
    case Imf::PXR24_COMPRESSION: return 16;
    case Imf::PIZ_COMPRESSION:
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION:
    case Imf::DWAA_COMPRESSION: return 32;
    default: return 256;
  }
}

// OpenEXR reserves, when it opens a part, two buffers per thread of one chunk each, sized by
// what the header declares (a block of scan lines, or one tile) however small the image is: a
// 523-byte file declaring tiles of 10 million by 4 pixels on an 8x4 image made it reserve a
// gigabyte, and on a many-core machine tens of gigabytes. A chunk may hold at most this many
// bytes as stored (a 16384-pixel-wide DWAB block of four float channels is exactly this).
constexpr double kMaxChunkBytes = double(64 << 20);

// Every size the file declares, checked before a pixel is allocated (giq/image/io.h).
void check_declared_sizes(const fs::path& path, const Imf::MultiPartInputFile& file) {
  int64_t channels = 0;
  double least_file_bytes = 0.0;
  std::string declared;
  for (int part = 0; part < file.parts(); ++part) {
    const Imf::Header& h = file.header(part);
    const Imath::Box2i dw = h.dataWindow();
    const int64_t w = int64_t(dw.max.x) - dw.min.x + 1, hgt = int64_t(dw.max.y) - dw.min.y + 1;
    const std::string field = "part " + std::to_string(part) + ".dataWindow";
    if (w <= 0 || hgt <= 0 || w > (1 << 20) || hgt > (1 << 20))
      throw InputError(path.string(), field,
                       "size " + std::to_string(w) + "x" + std::to_string(hgt) + " out of range (1..1048576)");
    double pixel_bytes = 0.0;
    for (auto c = h.channels().begin(); c != h.channels().end(); ++c, ++channels) pixel_bytes += c.channel().type == Imf::HALF ? 2.0 : 4.0;
    const double stored = double(w) * double(hgt) * pixel_bytes;
    check_decoded_size(path, field, w, hgt, std::max<int64_t>(channels, 1));
    if (h.hasTileDescription()) {
      // A tile larger than the image in a direction is legal but only wastes memory: at most
      // the data window, or 64 pixels (the smallest common tile side) for a small image.
      const Imf::TileDescription& t = h.tileDescription();
      const std::string tw = "part " + std::to_string(part) + ".tiles";
      if (int64_t(t.xSize) > std::max<int64_t>(w, 64) || int64_t(t.ySize) > std::max<int64_t>(hgt, 64))
        throw InputError(path.string(), tw,
                         "tiles of " + std::to_string(t.xSize) + "x" + std::to_string(t.ySize) + " pixels on a " + std::to_string(w) + "x" +
                             std::to_string(hgt) + " image; expected tiles no larger than the image (or 64 pixels)");
      if (double(t.xSize) * double(t.ySize) * pixel_bytes > kMaxChunkBytes)
        throw InputError(path.string(), tw,
                         "a tile of " + std::to_string(t.xSize) + "x" + std::to_string(t.ySize) + " pixels holds more than " +
                             std::to_string(int64_t(kMaxChunkBytes) >> 20) + " MiB; expected smaller tiles");
    } else if (double(w) * lines_per_chunk(h.compression()) * pixel_bytes > kMaxChunkBytes) {
      throw InputError(path.string(), field,
                       std::to_string(w) + " pixels per line in blocks of " + std::to_string(lines_per_chunk(h.compression())) +
                           " lines hold more than " + std::to_string(int64_t(kMaxChunkBytes) >> 20) +
                           " MiB a block; expected a narrower image or a codec with fewer lines per block");
    }
    declared = std::to_string(w) + "x" + std::to_string(hgt) + " pixels of " + std::to_string(channels) + " channels";
    if (const double ratio = max_compression_ratio(h.compression()); ratio > 0.0) least_file_bytes += stored / ratio;
  }
  check_file_can_hold(path, "dataWindow", least_file_bytes, "the " + declared + " it declares");
}

// The header against the file, before OpenEXR reads it. The library sizes a string or an
// opaque attribute by what the file declares and fills it afterwards (an 800-byte file
// declaring a 2 GB attribute costs seconds and gigabytes before it fails), a preview attribute
// declares its own width and height, and typed attributes (a channel list, an int) are read by
// their own layout, not by the size the file gives them, so a size that disagrees shifts
// everything after it. Each attribute's value must therefore fit in the file and fill exactly
// its declared size. Layout (OpenEXR file layout, "Header"): magic, version with flags, then per
// part attributes (name\0 type\0 int32 size, value), each header ended by an empty name, a
// multi-part file's list of headers by an empty header.
void check_header(const fs::path& path) {
  std::error_code ec;
  const uint64_t file_size = fs::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (!in || ec) return;  // the library reports what it cannot open
  std::string field = "header";
  auto fail = [&](const std::string& message) { throw InputError(path.string(), field, message); };
  auto int32 = [&] {
    unsigned char b[4];
    if (!in.read(reinterpret_cast<char*>(b), 4)) fail("ends early; the file is truncated");
    return int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24);
  };
  auto text = [&](const char* what) {
    std::string t;
    for (char c; in.get(c) && c != '\0';)
      if ((t += c).size() > 255) fail(std::string("an attribute ") + what + " is longer than 255 bytes");
    if (!in) fail("ends early; the file is truncated");
    return t;
  };
  // Types whose value has one fixed size (OpenEXR's standard attribute types).
  static const std::map<std::string, int32_t> fixed = {
      {"int", 4},          {"float", 4},     {"double", 8},     {"box2i", 16},       {"box2f", 16},
      {"v2i", 8},          {"v2f", 8},       {"v2d", 16},       {"v3i", 12},         {"v3f", 12},
      {"v3d", 24},         {"m33f", 36},     {"m33d", 72},      {"m44f", 64},        {"m44d", 128},
      {"compression", 1},  {"lineOrder", 1}, {"envmap", 1},     {"deepImageState", 1}, {"chromaticities", 32},
      {"keycode", 28},     {"timecode", 8},  {"rational", 8},   {"tiledesc", 9}};
  (void)int32();  // magic: read_image checked it
  const bool multipart = (uint32_t(int32()) & 0x1000u) != 0;
  for (int part = 0;; ++part) {
    if (multipart && part > 0 && in.peek() == 0) return;  // the empty header ending the list
    for (std::string name = text("name"); !name.empty(); name = text("name")) {
      field = (multipart ? "part " + std::to_string(part) + " " : "") + "attribute '" + name + "'";
      const std::string type = text("type");
      const int32_t size = int32();
      const uint64_t start = uint64_t(in.tellg()), left = file_size - start;
      if (size < 0 || uint64_t(size) > left)
        fail("declares " + std::to_string(size) + " bytes; the file has " + std::to_string(left) + " left");
      const uint64_t end = start + uint64_t(size);
      if (auto f = fixed.find(type); f != fixed.end() && f->second != size) {
        fail("is a " + type + " of " + std::to_string(size) + " bytes; expected " + std::to_string(f->second));
      } else if (type == "chlist") {  // entries (name\0, 16 bytes) up to an empty name
        for (std::string channel = text("channel name"); !channel.empty(); channel = text("channel name"))
          in.seekg(16, std::ios::cur);
        if (uint64_t(in.tellg()) != end) fail("its channel list does not fill its " + std::to_string(size) + " bytes");
      } else if (type == "preview" && (size < 8 || 8.0 + 4.0 * double(uint32_t(int32())) * double(uint32_t(int32())) != size)) {
        fail("its preview image does not fill its " + std::to_string(size) + " bytes");
      } else if (type == "stringvector") {  // int32 length, then the bytes, to the end
        while (uint64_t(in.tellg()) < end) {
          const int32_t n = int32();
          if (n < 0 || uint64_t(in.tellg()) + uint64_t(n) > end)
            fail("holds a string of " + std::to_string(n) + " bytes beyond its " + std::to_string(size));
          in.seekg(n, std::ios::cur);
        }
      }
      in.seekg(std::streamoff(end));
      if (!in) fail("ends early; the file is truncated");
    }
    if (!multipart) return;
  }
}

}  // namespace

void write_exr(const Image& image, const fs::path& path, const ExrOptions& options) {
  if (image.width() <= 0 || image.height() <= 0)
    throw InputError(path.string(), "", "cannot write an empty image (" + std::to_string(image.width()) + "x" +
                                            std::to_string(image.height()) + ") as EXR");
  // Everything the library may reject (channel names, attributes) happens inside the atomic
  // writer, so a failure leaves neither the final file nor a temporary behind.
  enable_threads();
  write_atomically(path, [&](const fs::path& tmp) {
    try {
      Imf::Header header(image.width(), image.height());
      header.compression() = to_imf(options.compression);
      for (const auto& name : image.channel_names()) {
        const bool half = options.half_channels.count(name) > 0;
        header.channels().insert(name, Imf::Channel(half ? Imf::HALF : Imf::FLOAT));
      }
      for (const auto& [key, value] : image.metadata) {
        // A key that names a standard attribute (channels, compression, dataWindow...) would
        // change the file's structure or be rejected by the library; refuse it clearly.
        if (header.find(key) != header.end())
          throw InputError(path.string(), "metadata." + key, "key collides with a standard EXR header attribute");
        header.insert(key, Imf::StringAttribute(value));
      }

      // OpenEXR does not convert float to half on output, so half channels get a converted
      // copy (Imath's half rounds to nearest even; out-of-range values become inf).
      Imf::FrameBuffer fb;
      std::vector<std::vector<Imath::half>> halves;
      for (const auto& name : image.channel_names()) {
        const float* src = image.channel(name);
        if (options.half_channels.count(name)) {
          auto& h = halves.emplace_back(src, src + image.pixel_count());
          fb.insert(name, Imf::Slice(Imf::HALF, (char*)h.data(), sizeof(Imath::half),
                                     sizeof(Imath::half) * size_t(image.width())));
        } else {
          fb.insert(name, Imf::Slice(Imf::FLOAT, (char*)src, sizeof(float), sizeof(float) * size_t(image.width())));
        }
      }
      Imf::OutputFile out(tmp.c_str(), header);
      out.setFrameBuffer(fb);
      out.writePixels(image.height());
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      throw InputError(path.string(), "", std::string("cannot write EXR: ") + e.what());
    }
  });
}

Image read_exr(const fs::path& path) {
  enable_threads();
  try {
    check_header(path);
    Imf::MultiPartInputFile file(path.c_str());
    check_declared_sizes(path, file);
    Image image;
    Imath::Box2i window;
    // A multi-part file (one part per layer, as some tools write) is merged into one image;
    // every part must cover the same pixels.
    for (int part = 0; part < file.parts(); ++part) {
      const Imf::Header& h = file.header(part);
      if (h.hasType() && Imf::isDeepData(h.type()))
        throw InputError(path.string(), "part " + std::to_string(part), "deep EXR data is not supported");
      const Imath::Box2i dw = h.dataWindow();
      const long long w = (long long)dw.max.x - dw.min.x + 1, hgt = (long long)dw.max.y - dw.min.y + 1;
      if (part == 0) {
        window = dw;
        image = Image(int(w), int(hgt));
      } else if (dw != window) {
        throw InputError(path.string(), "part " + std::to_string(part) + ".dataWindow",
                         "differs from part 0's; every part must cover the same pixels");
      }
      for (auto a = h.begin(); a != h.end(); ++a) {
        if (auto* s = dynamic_cast<const Imf::StringAttribute*>(&a.attribute())) {
          if (std::string(a.name()) == "name" || std::string(a.name()) == "type") continue;
          image.metadata[current_key(a.name())] = s->value();
        }
      }
      const std::string part_prefix = (file.parts() > 1 && h.hasName()) ? h.name() + "." : "";
      Imf::FrameBuffer fb;
      for (auto c = h.channels().begin(); c != h.channels().end(); ++c) {
        if (c.channel().xSampling != 1 || c.channel().ySampling != 1)
          throw InputError(path.string(), c.name(), "sub-sampled channels are not supported");
        std::string name = c.name();
        if (image.has_channel(name)) name = part_prefix + name;
        if (image.has_channel(name))
          throw InputError(path.string(), name, "channel appears twice in the file");
        float* plane = image.add_channel(name);
        // HALF and UINT channels are converted to float by the library.
        fb.insert(c.name(), Imf::Slice::Make(Imf::FLOAT, plane, dw, sizeof(float), sizeof(float) * size_t(w)));
      }
      Imf::InputPart in(file, part);
      in.setFrameBuffer(fb);
      in.readPixels(dw.min.y, dw.max.y);
    }
    return image;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path.string(), "", std::string("cannot read EXR: ") + e.what());
  }
}

}  // namespace giq::image
