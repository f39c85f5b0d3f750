// KHR_draco_mesh_compression and EXT_meshopt_compression: a grid with normals, texture
// coordinates and vertex colours is written plain, then compressed with the codecs' own
// encoders (Debian's libdraco and libmeshoptimizer), and each compressed file must load to the
// plain file's triangles within what the encoding keeps: meshopt's codecs are lossless (its
// octahedral filter keeps 8 bits per normal component here), Draco's quantises positions to
// 16 bits and keeps the rest exact. Damaged streams give one clear error.
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gtest/gtest.h>
#include <dlfcn.h>
#include <meshoptimizer.h>
#include <stb_image.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "giq/base/error.h"
#include "giq/scenes/scene.h"
#include "gltf_builder.h"
#include "support/scratch.h"

namespace giq::scenes {
namespace {

using nlohmann::json;
using giq::test::Doc;

constexpr int kN = 8;  // quads per side

struct Grid {
  std::vector<float> pos, nrm, uv;  // 3, 3, 2 per vertex
  std::vector<uint8_t> col;         // RGBA8 per vertex
  std::vector<uint32_t> idx;
  size_t vertices() const { return pos.size() / 3; }
};

// A height field z = 0.3 sin(2x) cos(y) over [-1, 1]^2, with its analytic normals.
Grid make_grid() {
  Grid g;
  for (int j = 0; j <= kN; ++j)
    for (int i = 0; i <= kN; ++i) {
      const float x = -1.0f + 2.0f * i / kN, y = -1.0f + 2.0f * j / kN;
      const float z = 0.3f * std::sin(2.0f * x) * std::cos(y);
      const glm::vec3 n = glm::normalize(glm::vec3(-0.6f * std::cos(2.0f * x) * std::cos(y), 0.3f * std::sin(2.0f * x) * std::sin(y), 1.0f));
      g.pos.insert(g.pos.end(), {x, y, z});
      g.nrm.insert(g.nrm.end(), {n.x, n.y, n.z});
      g.uv.insert(g.uv.end(), {float(i) / kN, float(j) / kN});
      g.col.insert(g.col.end(), {uint8_t(30 * i), uint8_t(30 * j), uint8_t(255 - 20 * i), uint8_t(200 + j)});
    }
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const uint32_t a = uint32_t(j * (kN + 1) + i), b = a + 1, c = a + kN + 1, d = c + 1;
      g.idx.insert(g.idx.end(), {a, b, d, a, d, c});
    }
  return g;
}

std::filesystem::path write_plain(const Grid& g, const std::filesystem::path& dir) {
  Doc d;
  const size_t n = g.vertices();
  auto attr = [&](const void* data, size_t bytes, int ct, const char* type, bool normalized) {
    const int v = d.view({{"buffer", 0}, {"byteOffset", d.append(data, bytes)}, {"byteLength", bytes}});
    return d.accessor({{"bufferView", v}, {"componentType", ct}, {"count", n}, {"type", type}, {"normalized", normalized}});
  };
  const int p = attr(g.pos.data(), g.pos.size() * 4, 5126, "VEC3", false);
  const int nm = attr(g.nrm.data(), g.nrm.size() * 4, 5126, "VEC3", false);
  const int uv = attr(g.uv.data(), g.uv.size() * 4, 5126, "VEC2", false);
  const int c = attr(g.col.data(), g.col.size(), 5121, "VEC4", true);
  const int iv = d.view({{"buffer", 0}, {"byteOffset", d.append(g.idx.data(), g.idx.size() * 4)}, {"byteLength", g.idx.size() * 4}});
  const int i = d.accessor({{"bufferView", iv}, {"componentType", 5125}, {"count", g.idx.size()}, {"type", "SCALAR"}});
  d.primitive({{"POSITION", p}, {"NORMAL", nm}, {"TEXCOORD_0", uv}, {"COLOR_0", c}}, i);
  return d.write(dir, "plain.gltf", false);
}

// gltfpack's layout: compressed bytes in the .glb's BIN chunk, the views on a placeholder
// buffer without data. Normals as 8-bit octahedral (KHR_mesh_quantization), indices as
// 16-bit TRIANGLES, the rest as ATTRIBUTES.
std::filesystem::path write_meshopt(const Grid& g, const std::filesystem::path& dir, bool damage = false) {
  Doc d;
  d.require("EXT_meshopt_compression");
  d.require("KHR_mesh_quantization");
  const size_t n = g.vertices();
  size_t fallback = 0;  // bytes of the placeholder buffer used so far
  auto compressed = [&](const std::vector<unsigned char>& encoded, size_t stride, size_t count, const char* mode, const char* filter, bool vertex) {
    json ext = {{"buffer", 0}, {"byteOffset", d.append(encoded.data(), encoded.size())}, {"byteLength", encoded.size()},
                {"byteStride", stride}, {"count", count}, {"mode", mode}};
    if (filter) ext["filter"] = filter;
    json v = {{"buffer", 1}, {"byteOffset", fallback}, {"byteLength", stride * count}, {"extensions", {{"EXT_meshopt_compression", ext}}}};
    if (vertex) v["byteStride"] = stride;
    fallback += (stride * count + 3) / 4 * 4;
    return d.view(v);
  };
  auto vertex_stream = [&](const void* data, size_t stride, const char* filter = nullptr) {
    std::vector<unsigned char> enc(meshopt_encodeVertexBufferBound(n, stride));
    enc.resize(meshopt_encodeVertexBuffer(enc.data(), enc.size(), data, n, stride));
    if (damage) enc.resize(enc.size() - 8);  // cut into the tail block
    return compressed(enc, stride, n, "ATTRIBUTES", filter, true);
  };
  auto accessor = [&](int view, int ct, const char* type, bool normalized) {
    return d.accessor({{"bufferView", view}, {"componentType", ct}, {"count", n}, {"type", type}, {"normalized", normalized}});
  };
  const int p = accessor(vertex_stream(g.pos.data(), 12), 5126, "VEC3", false);
  std::vector<float> n4;
  for (size_t i = 0; i < n; ++i) n4.insert(n4.end(), {g.nrm[3 * i], g.nrm[3 * i + 1], g.nrm[3 * i + 2], 0.0f});
  std::vector<int8_t> oct(4 * n);
  meshopt_encodeFilterOct(oct.data(), n, 4, 8, n4.data());
  const int nm = accessor(vertex_stream(oct.data(), 4, "OCTAHEDRAL"), 5120, "VEC3", true);
  const int uv = accessor(vertex_stream(g.uv.data(), 8), 5126, "VEC2", false);
  const int c = accessor(vertex_stream(g.col.data(), 4), 5121, "VEC4", true);
  std::vector<unsigned char> ienc(meshopt_encodeIndexBufferBound(g.idx.size(), n));
  ienc.resize(meshopt_encodeIndexBuffer(ienc.data(), ienc.size(), g.idx.data(), g.idx.size()));
  const int iv = compressed(ienc, 2, g.idx.size(), "TRIANGLES", nullptr, false);
  const int i = d.accessor({{"bufferView", iv}, {"componentType", 5123}, {"count", g.idx.size()}, {"type", "SCALAR"}});
  d.primitive({{"POSITION", p}, {"NORMAL", nm}, {"TEXCOORD_0", uv}, {"COLOR_0", c}}, i);
  d.j["buffers"] = {{{"byteLength", 0}}, {{"byteLength", fallback}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
  return d.write(dir, damage ? "damaged_meshopt.glb" : "meshopt.glb", true);
}

// The Draco layout: one buffer view holds the mesh; the primitive's accessors have no view.
// `miscount` is added to every accessor's count, which then no longer matches the data.
std::filesystem::path write_draco(const Grid& g, const std::filesystem::path& dir, bool damage = false, size_t miscount = 0) {
  draco::TriangleSoupMeshBuilder b;
  const int faces = int(g.idx.size() / 3);
  b.Start(faces);
  const int ap = b.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int an = b.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  const int at = b.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  const int ac = b.AddAttribute(draco::GeometryAttribute::COLOR, 4, draco::DT_UINT8);
  for (int f = 0; f < faces; ++f) {
    const uint32_t* t = &g.idx[3 * size_t(f)];
    const draco::FaceIndex fi(f);
    b.SetAttributeValuesForFace(ap, fi, &g.pos[3 * t[0]], &g.pos[3 * t[1]], &g.pos[3 * t[2]]);
    b.SetAttributeValuesForFace(an, fi, &g.nrm[3 * t[0]], &g.nrm[3 * t[1]], &g.nrm[3 * t[2]]);
    b.SetAttributeValuesForFace(at, fi, &g.uv[2 * t[0]], &g.uv[2 * t[1]], &g.uv[2 * t[2]]);
    b.SetAttributeValuesForFace(ac, fi, &g.col[4 * t[0]], &g.col[4 * t[1]], &g.col[4 * t[2]]);
  }
  std::unique_ptr<draco::Mesh> mesh = b.Finalize();
  draco::Encoder enc;
  enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 16);
  draco::EncoderBuffer eb;
  EXPECT_TRUE(enc.EncodeMeshToBuffer(*mesh, &eb).ok());
  // The decoded counts, which the placeholder accessors must declare.
  draco::DecoderBuffer db;
  db.Init(eb.data(), eb.size());
  const std::unique_ptr<draco::Mesh> back = draco::Decoder().DecodeMeshFromBuffer(&db).value();
  std::vector<unsigned char> bytes(eb.data(), eb.data() + eb.size());
  if (damage) bytes.resize(bytes.size() / 2);

  Doc d;
  d.require("KHR_draco_mesh_compression");
  const int v = d.view({{"buffer", 0}, {"byteOffset", d.append(bytes.data(), bytes.size())}, {"byteLength", bytes.size()}});
  const size_t points = back->num_points();
  auto placeholder = [&](int ct, const char* type, bool normalized) {
    return d.accessor({{"componentType", ct}, {"count", points + miscount}, {"type", type}, {"normalized", normalized}});
  };
  const int p = placeholder(5126, "VEC3", false), nm = placeholder(5126, "VEC3", false), uv = placeholder(5126, "VEC2", false),
            c = placeholder(5121, "VEC4", true);
  const int i = d.accessor({{"componentType", 5125}, {"count", back->num_faces() * 3 + miscount}, {"type", "SCALAR"}});
  const auto id = [&](int att) { return mesh->attribute(att)->unique_id(); };
  d.primitive({{"POSITION", p}, {"NORMAL", nm}, {"TEXCOORD_0", uv}, {"COLOR_0", c}}, i,
              {{"KHR_draco_mesh_compression",
                {{"bufferView", v}, {"attributes", {{"POSITION", id(ap)}, {"NORMAL", id(an)}, {"TEXCOORD_0", id(at)}, {"COLOR_0", id(ac)}}}}}});
  return d.write(dir, damage ? "damaged_draco.gltf" : miscount ? "miscounted_draco.gltf" : "draco.gltf", false);
}

// A triangle's corners in world space, with their attributes.
struct Corner {
  glm::dvec3 p;
  glm::vec3 n;
  glm::vec2 uv;
  glm::vec4 c;
};
using Triangle = std::array<Corner, 3>;

// The scene's triangles in a canonical order: each rotated to start at its smallest corner
// (the winding kept), then sorted, on positions rounded far coarser than any encoding error.
std::vector<Triangle> triangles(const Scene& s) {
  std::vector<Triangle> out;
  for (const Mesh& m : s.meshes)
    for (const glm::uvec3& t : m.triangles) {
      Triangle tri;
      for (int k = 0; k < 3; ++k)
        tri[k] = {s.origin + glm::dvec3(m.positions[t[k]]), m.normals[t[k]], m.uvs[t[k]], m.colors[t[k]]};
      out.push_back(tri);
    }
  auto key = [](const Corner& c) { return std::array<long, 3>{std::lround(c.p.x * 1e3), std::lround(c.p.y * 1e3), std::lround(c.p.z * 1e3)}; };
  for (Triangle& t : out) {
    const int first = int(std::min_element(t.begin(), t.end(), [&](const Corner& a, const Corner& b) { return key(a) < key(b); }) - t.begin());
    std::rotate(t.begin(), t.begin() + first, t.end());
  }
  std::sort(out.begin(), out.end(), [&](const Triangle& a, const Triangle& b) {
    return std::array{key(a[0]), key(a[1]), key(a[2])} < std::array{key(b[0]), key(b[1]), key(b[2])};
  });
  return out;
}

void expect_same_triangles(const Scene& got, const Scene& want, double pos_tol, float normal_tol) {
  const std::vector<Triangle> a = triangles(got), b = triangles(want);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), size_t(2 * kN * kN));
  for (size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const Corner &x = a[i][k], &y = b[i][k];
      ASSERT_LE(glm::length(x.p - y.p), pos_tol) << "triangle " << i << " corner " << k;
      ASSERT_LE(glm::length(x.n - y.n), normal_tol) << "triangle " << i << " corner " << k;
      ASSERT_EQ(x.uv, y.uv) << "triangle " << i << " corner " << k;
      ASSERT_EQ(x.c, y.c) << "triangle " << i << " corner " << k;
    }
}

// libdraco.a carries its own tinygltf and stb_image: linked before libtinygltf and libstb, it
// would replace them in the executable (a different tinygltf::Model layout: heap corruption).
TEST(CompressionLink, TinygltfAndStbComeFromTheirOwnLibraries) {
  Dl_info info{};
  ASSERT_NE(dladdr(reinterpret_cast<void*>(&stbi_failure_reason), &info), 0);
  EXPECT_NE(std::string(info.dli_fname).find("libstb"), std::string::npos) << info.dli_fname;
  // A non-virtual member function pointer holds the function's address in its first word.
  const auto member = &tinygltf::TinyGLTF::LoadASCIIFromString;
  void* address = nullptr;
  std::memcpy(&address, &member, sizeof address);
  ASSERT_NE(dladdr(address, &info), 0);
  EXPECT_NE(std::string(info.dli_fname).find("libtinygltf"), std::string::npos) << info.dli_fname;
}

class Compression : public ::testing::Test {
 protected:
  const std::filesystem::path dir = test::fresh_dir("compression");
  const Grid grid = make_grid();
};

TEST_F(Compression, MeshoptLoadsExactlyWithItsOctahedralNormals) {
  const Scene plain = load(write_plain(grid, dir));
  const Scene packed = load(write_meshopt(grid, dir));
  // Lossless codecs: positions, coordinates and colours bit for bit. Normals went through
  // 8-bit octahedral components: each off by at most half a step of 1/127 before
  // renormalisation, which stays within 2/127 of the unit vector.
  expect_same_triangles(packed, plain, 0.0, 2.0f / 127.0f);
}

TEST_F(Compression, DracoLoadsWithinItsQuantisation) {
  const Scene plain = load(write_plain(grid, dir));
  const Scene packed = load(write_draco(grid, dir));
  // 16-bit positions over the grid's largest side (2 m): within one step of 2/65535 m, as
  // the quantisation rounds to the nearest of them; the unquantised rest exactly.
  expect_same_triangles(packed, plain, 2.0 / 65535.0, 0.0f);
}

// Accessors whose counts do not match the Draco data (as some encoders write them): the
// decoded points and faces are what the extension describes, so they are used, with a warning.
TEST_F(Compression, DracoCountsThatDoNotMatchTheDataTakeTheDecodedData) {
  const Scene plain = load(write_plain(grid, dir));
  const Scene packed = load(write_draco(grid, dir, false, 7));
  expect_same_triangles(packed, plain, 2.0 / 65535.0, 0.0f);
  ASSERT_FALSE(packed.warnings.empty());
  EXPECT_NE(packed.warnings[0].find("the Draco data decodes to"), std::string::npos) << packed.warnings[0];
  EXPECT_NE(packed.warnings[0].find("(5 times in the file)"), std::string::npos) << packed.warnings[0];  // 4 attributes and the indices
  EXPECT_TRUE(load(write_draco(grid, dir)).warnings.empty());
}

// The same grid compressed once and kept in tests/data (as .glb files, a self-contained seed
// for the glTF fuzzer too): today's decoders still read them as the grid.
TEST_F(Compression, StoredFilesStillDecodeToTheGrid) {
  const Scene plain = load(write_plain(grid, dir));
  expect_same_triangles(load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "meshopt.glb"), plain, 0.0, 2.0f / 127.0f);
  expect_same_triangles(load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "draco.glb"), plain, 2.0 / 65535.0, 0.0f);
}

TEST_F(Compression, DamagedStreamsAreOneClearError) {
  const auto expect_error = [](const std::filesystem::path& path, const std::string& field) {
    try {
      (void)load(path);
      ADD_FAILURE() << path << " loaded";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  expect_error(write_meshopt(grid, dir, true), "bufferViews[0].extensions.EXT_meshopt_compression");
  expect_error(write_draco(grid, dir, true), "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression.bufferView");
}

}  // namespace
}  // namespace giq::scenes
