#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfPreviewImage.h>
#include <ImfStringAttribute.h>
#include <ImfTiledOutputFile.h>
#include <gtest/gtest.h>
#include <half.h>
#include <unistd.h>

#include <bit>
#include <cstring>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>

#include "giq/base/error.h"
#include "support/subprocess.h"
#include "giq/image/io.h"

namespace fs = std::filesystem;
using giq::image::Image;

namespace {

fs::path fresh_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("giq_exr_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

size_t entries(const fs::path& d) { return size_t(std::distance(fs::directory_iterator(d), fs::directory_iterator{})); }

// Every float32 class that must survive a round trip bit for bit.
std::vector<float> special_values() {
  const float inf = std::numeric_limits<float>::infinity();
  return {0.0f, -0.0f, 1.0f, -1.0f, 0.1f, 3.14159265f, 1e-8f, 1e6f, 3.4e38f, -3.4e38f, inf, -inf,
          std::numeric_limits<float>::quiet_NaN(), std::bit_cast<float>(0x7fa00001u) /* NaN payload */,
          std::numeric_limits<float>::denorm_min(), 1e-40f /* denormal */, -1e-42f,
          std::numeric_limits<float>::min(), 65504.0f, 123456.789f};
}

Image reference_like(int w, int h) {
  Image img(w, h);
  const auto special = special_values();
  const char* names[] = {"R", "G", "B", "indirect.R", "indirect.G", "indirect.B", "variance.R", "variance.G",
                         "variance.B", "N.X", "N.Y", "N.Z", "Z", "objectId", "spp"};
  uint32_t state = 12345u;
  for (const char* n : names) {
    float* p = img.add_channel(n);
    for (size_t i = 0; i < img.pixel_count(); ++i) {
      state = state * 1664525u + 1013904223u;  // LCG (Numerical Recipes): arbitrary bits
      p[i] = i < special.size() ? special[i] : std::bit_cast<float>(state);
    }
  }
  img.metadata["giq:scene_hash"] = "0123456789abcdef";
  img.metadata["giq:view"] = "front";
  img.metadata["giq:settings"] = "{\"spp\": 64, \"unicode\": \"\xc3\xa9\"}";
  return img;
}

void expect_bit_exact(const Image& a, const Image& b) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  ASSERT_EQ(a.channel_names().size(), b.channel_names().size());
  for (const auto& n : a.channel_names()) {
    ASSERT_TRUE(b.has_channel(n)) << n;
    const float* pa = a.channel(n);
    const float* pb = b.channel(n);
    for (size_t i = 0; i < a.pixel_count(); ++i)
      ASSERT_EQ(std::bit_cast<uint32_t>(pa[i]), std::bit_cast<uint32_t>(pb[i])) << n << " pixel " << i;
  }
}

}  // namespace

TEST(Exr, MultiLayerRoundTripIsBitExact) {
  fs::path d = fresh_dir("roundtrip");
  Image img = reference_like(37, 23);
  for (auto c : {giq::image::ExrOptions::Compression::Zip, giq::image::ExrOptions::Compression::None,
                 giq::image::ExrOptions::Compression::Piz}) {
    giq::image::ExrOptions opt;
    opt.compression = c;
    giq::image::write_exr(img, d / "a.exr", opt);
    Image back = giq::image::read_image(d / "a.exr");
    expect_bit_exact(img, back);
    for (const auto& [k, v] : img.metadata) EXPECT_EQ(back.metadata.at(k), v) << k;
  }
  EXPECT_EQ(entries(d), 1u);
}

TEST(Exr, HalfChannelsRoundTripRepresentableValuesExactly) {
  fs::path d = fresh_dir("half");
  Image img(8, 2);
  // Values exactly representable in binary16: integers up to 2048, powers of two down to the
  // smallest half denormal 2^-24, the largest half 65504, signed zeros and infinities.
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<float> v = {0.0f, -0.0f, 1.0f, 0.5f, 2048.0f, -3.0f, 65504.0f, std::ldexp(1.0f, -24),
                                std::ldexp(1.0f, -14), 0.099975586f /* 1638*2^-14 */, inf, -inf, 1.5f,
                                -0.25f, 1000.0f, 7.0f};
  float* a = img.add_channel("albedo.R");
  float* b = img.add_channel("R");
  for (size_t i = 0; i < v.size(); ++i) a[i] = v[i], b[i] = v[i] + 1e-7f;
  giq::image::ExrOptions opt;
  opt.half_channels = {"albedo.R"};
  giq::image::write_exr(img, d / "h.exr", opt);
  Image back = giq::image::read_image(d / "h.exr");
  for (size_t i = 0; i < v.size(); ++i) {
    EXPECT_EQ(std::bit_cast<uint32_t>(back.channel("albedo.R")[i]), std::bit_cast<uint32_t>(v[i])) << i;
    EXPECT_EQ(back.channel("R")[i], v[i] + 1e-7f);  // float32 channel untouched
  }
  // A value beyond the half range becomes inf, as io.h documents; NaN stays NaN.
  a[0] = 1e6f;
  a[1] = std::numeric_limits<float>::quiet_NaN();
  giq::image::write_exr(img, d / "h.exr", opt);
  back = giq::image::read_image(d / "h.exr");
  EXPECT_TRUE(std::isinf(back.channel("albedo.R")[0]));
  EXPECT_TRUE(std::isnan(back.channel("albedo.R")[1]));
}

TEST(Exr, ThrowingWriterLeavesNoPartialFile) {
  fs::path d = fresh_dir("atomic");
  Image good = reference_like(4, 4);
  giq::image::write_exr(good, d / "a.exr");
  const auto size_before = fs::file_size(d / "a.exr");
  // OpenEXR rejects an empty channel name while writing: the failure happens inside the
  // atomic writer, after the temporary file was named.
  Image bad = reference_like(4, 4);
  bad.add_channel("");
  EXPECT_THROW(giq::image::write_exr(bad, d / "a.exr"), giq::InputError);
  EXPECT_THROW(giq::image::write_exr(bad, d / "new.exr"), giq::InputError);
  EXPECT_EQ(entries(d), 1u);  // no temporary left, no new.exr
  EXPECT_EQ(fs::file_size(d / "a.exr"), size_before);
  expect_bit_exact(good, giq::image::read_image(d / "a.exr"));
}

TEST(Exr, MetadataKeyCollidingWithStandardAttributeIsRejected) {
  fs::path d = fresh_dir("collide");
  Image img(2, 2);
  img.add_channel("R");
  img.metadata["compression"] = "none";
  EXPECT_THROW(giq::image::write_exr(img, d / "a.exr"), giq::InputError);
  EXPECT_EQ(entries(d), 0u);
}

TEST(Exr, LegacyCamelCaseHeaderKeysAreReadUnderTheirSnakeCaseNames) {
  // References written before the header keys were unified (the committed goldens among them).
  fs::path d = fresh_dir("legacy_keys");
  Image img(2, 2);
  img.add_channel("R");
  img.metadata = {{"giq.sceneHash", "abc"}, {"giq.renderTime", "1.5"}, {"giq.nonFiniteSamples", "0"},
                  {"giq.gpu_ms", "0.25"}};
  giq::image::write_exr(img, d / "a.exr");
  const Image back = giq::image::read_image(d / "a.exr");
  EXPECT_EQ(back.metadata.at("giq.scene_hash"), "abc");
  EXPECT_EQ(back.metadata.at("giq.render_time"), "1.5");
  EXPECT_EQ(back.metadata.at("giq.nonfinite_samples"), "0");
  EXPECT_EQ(back.metadata.at("giq.gpu_ms"), "0.25");
  EXPECT_EQ(back.metadata.count("giq.sceneHash"), 0u);
}

TEST(Exr, TruncatedFileIsInputErrorNamingTheFile) {
  fs::path d = fresh_dir("truncated");
  Image img = reference_like(64, 64);
  giq::image::ExrOptions opt;
  opt.compression = giq::image::ExrOptions::Compression::None;
  giq::image::write_exr(img, d / "full.exr", opt);
  const auto size = fs::file_size(d / "full.exr");
  for (double keep : {0.9, 0.5, 0.1, 0.01}) {
    fs::copy_file(d / "full.exr", d / "cut.exr", fs::copy_options::overwrite_existing);
    fs::resize_file(d / "cut.exr", uintmax_t(double(size) * keep));
    try {
      giq::image::read_image(d / "cut.exr");
      ADD_FAILURE() << "truncated to " << keep << " was read without error";
    } catch (const giq::InputError& e) {
      EXPECT_EQ(e.file(), (d / "cut.exr").string());
    }
  }
}

TEST(Exr, MissingAndGarbageFilesAreInputErrors) {
  fs::path d = fresh_dir("garbage");
  EXPECT_THROW(giq::image::read_image(d / "nope.exr"), giq::InputError);
  EXPECT_THROW(giq::image::read_image(d), giq::InputError);
  {
    std::ofstream(d / "magic.exr", std::ios::binary) << "\x76\x2f\x31\x01 then nonsense follows here";
  }
  try {
    giq::image::read_image(d / "magic.exr");
    FAIL() << "garbage was read";
  } catch (const giq::InputError& e) {
    EXPECT_EQ(e.file(), (d / "magic.exr").string());
  }
  { std::ofstream(d / "empty.exr", std::ios::binary); }
  EXPECT_THROW(giq::image::read_image(d / "empty.exr"), giq::InputError);
}

TEST(Exr, UintAndHalfChannelsWrittenByOtherToolsReadAsFloat) {
  // A file as another renderer might write it: objectId as UINT, colour as HALF.
  fs::path d = fresh_dir("uint");
  const int w = 3, h = 2;
  Imf::Header header(w, h);
  header.channels().insert("objectId", Imf::Channel(Imf::UINT));
  header.channels().insert("R", Imf::Channel(Imf::HALF));
  header.insert("giq:view", Imf::StringAttribute("front"));
  std::vector<uint32_t> ids = {0, 1, 7, 65536, 16777216, 4000000000u};
  std::vector<Imath::half> r = {Imath::half(0.5f), Imath::half(1.0f), Imath::half(-2.0f),
                                Imath::half(0.099975586f), Imath::half(65504.0f), Imath::half(0.0f)};
  Imf::FrameBuffer fb;
  fb.insert("objectId", Imf::Slice(Imf::UINT, (char*)ids.data(), sizeof(uint32_t), sizeof(uint32_t) * w));
  fb.insert("R", Imf::Slice(Imf::HALF, (char*)r.data(), sizeof(Imath::half), sizeof(Imath::half) * w));
  {
    Imf::OutputFile out((d / "u.exr").c_str(), header);
    out.setFrameBuffer(fb);
    out.writePixels(h);
  }
  const Image img = giq::image::read_image(d / "u.exr");
  // Integers up to 2^24 are exact in float; 4e9 rounds to the nearest float.
  for (size_t i = 0; i < ids.size(); ++i) {
    EXPECT_EQ(img.channel("objectId")[i], float(ids[i])) << i;
    EXPECT_EQ(img.channel("R")[i], float(r[i])) << i;
  }
  EXPECT_EQ(img.metadata.at("giq:view"), "front");
}

namespace {

// An EXR whose header declares w x h RGB floats but whose pixels were never written: the file
// holds the header and an offset table, as a truncated or hand-edited file would.
fs::path declared_only(const fs::path& d, int w, int h, Imf::Compression compression) {
  const fs::path p = d / ("declared_" + std::to_string(w) + "x" + std::to_string(h) + ".exr");
  Imf::Header header(w, h);
  header.compression() = compression;
  for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
  { Imf::OutputFile out(p.c_str(), header); }
  return p;
}

std::string read_error(const fs::path& p) {
  try {
    giq::image::read_image(p);
  } catch (const giq::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Exr, DeclaredSizesAreCheckedBeforeAllocating) {
  fs::path d = fresh_dir("declared");
  // 20000^2 RGB floats decode to 4.47 GiB, over the 4 GiB every reader allows.
  const fs::path huge = declared_only(d, 20000, 20000, Imf::ZIP_COMPRESSION);
  const std::string e = read_error(huge);
  EXPECT_NE(e.find("20000x20000 pixels of 3 channels decode to 4.47 GiB; expected at most 4 GiB"), std::string::npos)
      << e;
  // 8000^2 fits in memory, but 768 MB of float pixels cannot be deflated into a file of a few
  // kilobytes: deflate reaches at most 1032:1, so the file would need 744 KB at least.
  for (Imf::Compression c : {Imf::NO_COMPRESSION, Imf::ZIP_COMPRESSION, Imf::PIZ_COMPRESSION}) {
    const fs::path p = declared_only(d, 8000, 8000, c);
    ASSERT_LT(fs::file_size(p), 744'186u);
    const std::string m = read_error(p);
    EXPECT_NE(m.find("cannot be stored in " + std::to_string(fs::file_size(p)) + " bytes"), std::string::npos) << m;
    EXPECT_NE(m.find("8000x8000"), std::string::npos) << m;
  }
  // A small image whose pixels compress to almost nothing is still read: the bound is the
  // codec's, not a guess.
  Image flat(512, 512);
  for (const char* c : {"R", "G", "B"}) flat.add_channel(c, 0.25f);
  giq::image::write_exr(flat, d / "flat.exr");
  EXPECT_EQ(giq::image::read_image(d / "flat.exr").channel("G")[511 * 512 + 7], 0.25f);
}

TEST(Exr, DeclaredChunksAreBoundedLikeTheImage) {
  // OpenEXR reserves two buffers per thread of one chunk each when it opens a file, sized by
  // the header whatever the image. A 400000-pixel line of three floats in ZIP's 16-line blocks
  // is 76.8 MB a block, over the 64 MiB allowed, though the image itself is 4.8 MB.
  fs::path d = fresh_dir("chunks");
  const std::string wide = read_error(declared_only(d, 400000, 1, Imf::ZIP_COMPRESSION));
  EXPECT_NE(wide.find("400000 pixels per line in blocks of 16 lines hold more than 64 MiB a block"), std::string::npos) << wide;

  // A tiled 8x4 image, written whole with 64x64 tiles (larger than the image: legal, and read).
  auto tiled = [&](int tile_x, int tile_y) {
    const fs::path p = d / ("tiled_" + std::to_string(tile_x) + "x" + std::to_string(tile_y) + ".exr");
    Imf::Header header(8, 4);
    header.setTileDescription(Imf::TileDescription(tile_x, tile_y, Imf::ONE_LEVEL));
    header.channels().insert("G", Imf::Channel(Imf::FLOAT));
    std::vector<float> g(32, 0.5f);
    Imf::FrameBuffer fb;
    fb.insert("G", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(g.data()), sizeof(float), 8 * sizeof(float)));
    Imf::TiledOutputFile out(p.c_str(), header);
    out.setFrameBuffer(fb);
    out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
    return p;
  };
  const fs::path ok = tiled(64, 64);
  EXPECT_EQ(giq::image::read_image(ok).channel("G")[31], 0.5f);
  // The same file with its tile width patched to 10 million (still one tile across, so the
  // file stays consistent): a few hundred bytes that made OpenEXR reserve 320 MB a buffer.
  std::string bytes = giq::test::slurp(ok);
  const std::string key("tiles\0tiledesc\0", 15);
  const size_t at = bytes.find(key);
  ASSERT_NE(at, std::string::npos);
  const uint32_t huge = 10'000'000;
  for (int k = 0; k < 4; ++k) bytes[at + key.size() + 4 + size_t(k)] = char(huge >> (8 * k) & 0xFFu);  // xSize, little-endian, after the size
  const fs::path patched = d / "tiled_huge.exr";
  std::ofstream(patched, std::ios::binary) << bytes;
  const std::string e = read_error(patched);
  EXPECT_NE(e.find("tiles of 10000000x64 pixels on a 8x4 image; expected tiles no larger than the image (or 64 pixels)"),
            std::string::npos)
      << e;
}

TEST(Exr, HeaderAttributesMustFitTheFileAndFillTheirSize) {
  fs::path d = fresh_dir("header");
  Image im(4, 2);
  for (const char* c : {"R", "G", "B"}) im.add_channel(c, 0.5f);
  im.metadata["giq:view"] = "front";
  giq::image::write_exr(im, d / "ok.exr");
  std::string bytes;
  {
    std::ifstream in(d / "ok.exr", std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto set_int32 = [](std::string& b, size_t at, int32_t v) { b.replace(at, 4, reinterpret_cast<const char*>(&v), 4); };
  auto error_of = [&](const std::string& b, const std::string& name) {
    std::ofstream(d / name, std::ios::binary) << b;
    return read_error(d / name);
  };
  // A string declaring 2 GB: OpenEXR would size it first and fail at the end of the file.
  const std::string view = std::string("giq:view\0string\0", 16);
  const size_t v = bytes.find(view);
  ASSERT_NE(v, std::string::npos);
  std::string big = bytes;
  set_int32(big, v + view.size(), 2'000'000'000);
  const std::string e1 = error_of(big, "big_string.exr");
  EXPECT_NE(e1.find("attribute 'giq:view': declares 2000000000 bytes; the file has"), std::string::npos) << e1;
  // A channel list whose size says 4 bytes more than its entries take: OpenEXR reads the list
  // by its entries, so every later attribute would be read 4 bytes early.
  const std::string chlist = std::string("channels\0chlist\0", 16);
  const size_t c = bytes.find(chlist);
  ASSERT_NE(c, std::string::npos);
  std::string shifted = bytes;
  int32_t size = 0;
  std::memcpy(&size, bytes.data() + c + chlist.size(), 4);
  set_int32(shifted, c + chlist.size(), size + 4);
  shifted.insert(c + chlist.size() + 4 + size_t(size), 4, 'x');
  const std::string e2 = error_of(shifted, "shifted.exr");
  EXPECT_NE(e2.find("attribute 'channels': its channel list does not fill its " + std::to_string(size + 4) + " bytes"),
            std::string::npos)
      << e2;
  // A one-byte enum that claims 2 bytes.
  std::string wide_int = bytes;
  const size_t i = bytes.find(std::string("lineOrder\0lineOrder\0", 20));
  ASSERT_NE(i, std::string::npos);
  set_int32(wide_int, i + 20, 2);
  const std::string e3 = error_of(wide_int, "wide.exr");
  EXPECT_NE(e3.find("attribute 'lineOrder': is a lineOrder of 2 bytes; expected 1"), std::string::npos) << e3;
  // The untouched file still reads.
  EXPECT_EQ(giq::image::read_image(d / "ok.exr").metadata.at("giq:view"), "front");

  // A preview declaring 2^32-1 x 2^32-1 pixels in its 24 bytes (found by the exr fuzzer: the
  // check itself overflowed 64-bit integers).
  {
    Imf::Header header(2, 2);
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    header.setPreviewImage(Imf::PreviewImage(2, 2));
    std::vector<float> r(4, 1.0f);
    Imf::FrameBuffer fb;
    fb.insert("R", Imf::Slice(Imf::FLOAT, (char*)r.data(), sizeof(float), 2 * sizeof(float)));
    Imf::OutputFile out((d / "preview.exr").c_str(), header);
    out.setFrameBuffer(fb);
    out.writePixels(2);
  }
  std::ifstream pin(d / "preview.exr", std::ios::binary);
  std::string preview((std::istreambuf_iterator<char>(pin)), {});
  const std::string tag = std::string("preview\0preview\0", 16);
  const size_t pv = preview.find(tag);
  ASSERT_NE(pv, std::string::npos);
  EXPECT_EQ(giq::image::read_image(d / "preview.exr").width(), 2);
  set_int32(preview, pv + tag.size() + 4, -1);
  set_int32(preview, pv + tag.size() + 8, -1);
  const std::string e4 = error_of(preview, "preview_huge.exr");
  EXPECT_NE(e4.find("attribute 'preview': its preview image does not fill its 24 bytes"), std::string::npos) << e4;
}
