#include "gltf_materials.h"

#include <stb_image.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <thread>
#include <tuple>

#include "gltf_bytes.h"
#include "png_texels.h"

namespace giq::scenes::gltf {
namespace {

// Larger images are refused before decoding so a forged header cannot exhaust memory: 2^26
// texels are 256 MiB as 8-bit RGBA, 1 GiB as float. All of a scene's textures together hold
// at most 2 GiB (512 textures of 1024^2 at 8 bits).
constexpr int kMaxImageSide = 16384;
constexpr int64_t kMaxImageTexels = int64_t(1) << 26;
constexpr int64_t kMaxTextureBytes = int64_t(2) << 30;

std::string decode_failure() {
  const char* r = stbi_failure_reason();
  return r ? r : "unknown reason";
}

class TextureTable : public TextureDecoding {
 public:
  TextureTable(const Context& ctx, const Document& doc, std::vector<Texture>& out) : ctx_(ctx), doc_(doc), out_(out) {}

  // Scene texture index for glTF texture `index` used from `field` in the given colour space.
  int use(int index, const std::string& field, bool srgb) {
    const auto& m = ctx_.model;
    if (index < 0 || size_t(index) >= m.textures.size())
      ctx_.fail(field + ".index", "is " + std::to_string(index) + "; the file has " + std::to_string(m.textures.size()) + " textures");
    const auto& t = m.textures[size_t(index)];
    const std::string where = index_path("textures", size_t(index));
    if (t.source < 0)
      ctx_.fail(where + ".source", "missing; textures whose image comes only from an extension (e.g. KHR_texture_basisu) are not supported");
    if (size_t(t.source) >= m.images.size())
      ctx_.fail(where + ".source", "is " + std::to_string(t.source) + "; the file has " + std::to_string(m.images.size()) + " images");
    if (t.sampler >= 0 && size_t(t.sampler) >= m.samplers.size())
      ctx_.fail(where + ".sampler", "is " + std::to_string(t.sampler) + "; the file has " + std::to_string(m.samplers.size()) + " samplers");
    const auto key = std::make_tuple(t.source, t.sampler, srgb);
    if (auto it = index_.find(key); it != index_.end()) return it->second;

    Texture tex;
    const auto& image = m.images[size_t(t.source)];
    tex.name = !image.name.empty() ? image.name : !image.uri.empty() ? image.uri : "image" + std::to_string(t.source);
    if (t.sampler >= 0) {
      const auto& s = m.samplers[size_t(t.sampler)];
      const std::string sw = index_path("samplers", size_t(t.sampler));
      tex.wrap_s = wrap(s.wrapS, sw + ".wrapS");
      tex.wrap_t = wrap(s.wrapT, sw + ".wrapT");
      if (s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) tex.filter = Filter::Nearest;
      else if (s.magFilter == -1 || s.magFilter == TINYGLTF_TEXTURE_FILTER_LINEAR) tex.filter = Filter::Linear;
      else ctx_.fail(sw + ".magFilter", "is " + std::to_string(s.magFilter) + "; expected 9728 (NEAREST) or 9729 (LINEAR)");
      if (s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST || s.minFilter == TINYGLTF_TEXTURE_FILTER_LINEAR) tex.mip_maps = false;
      else if (s.minFilter != -1 && (s.minFilter < TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST || s.minFilter > TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR))
        ctx_.fail(sw + ".minFilter", "is " + std::to_string(s.minFilter) + "; expected 9728, 9729 or 9984 to 9987 (glTF 2.0, 5.26)");
    }
    requests_.push_back({out_.size(), t.source, srgb});
    out_.push_back(std::move(tex));
    return index_[key] = int(out_.size()) - 1;
  }

  // A metallic-roughness texture made from a specular-glossiness one (glTF texture `index`):
  // G = roughness = 1 - glossiness_factor x A, B = metallic 1 (the material's metallic factor
  // is 0). Made in finish(), once the source's texels are decoded.
  int roughness_from_glossiness(int index, const std::string& field, double glossiness_factor) {
    const int source = use(index, field, false);
    const auto key = std::make_pair(source, glossiness_factor);
    if (auto it = derived_.find(key); it != derived_.end()) return it->second;
    derived_jobs_.push_back({out_.size(), size_t(source), glossiness_factor, field});
    out_.push_back(out_[size_t(source)]);  // name and sampler
    return derived_[key] = int(out_.size()) - 1;
  }

  // Checks every image's header (errors now, in first-use order) and starts decoding them on
  // worker threads, one per core, while the caller goes on (the loader reads the geometry).
  void start() {
    for (const auto& r : requests_) {
      if (!headers_.count(r.image)) headers_[r.image] = header(r.image), images_.push_back(r.image);
      const Header& h = headers_[r.image];
      // 8-bit texels serve both colour spaces; 16-bit ones become floats once per colour space.
      if (h.sixteen ? counted_.insert({r.image, r.srgb}).second : counted_.insert({r.image, false}).second)
        count_bytes(int64_t(h.width) * h.height * (h.sixteen ? 16 : 4), index_path("images", size_t(r.image)));
    }
    raw_.resize(images_.size());
    const size_t threads = std::min<size_t>(images_.size(), std::max(1u, std::thread::hardware_concurrency()));
    for (size_t t = 0; t < threads; ++t)
      workers_.emplace_back([this] {
        for (size_t i; (i = next_.fetch_add(1)) < images_.size();) {
          try {
            raw_[i] = decode(images_[i], headers_.at(images_[i]));
          } catch (const std::exception& e) {  // out of memory: reported by finish() like any decoding failure
            raw_[i].error = std::string("cannot decode the image (") + e.what() + ")";
          }
        }
      });
  }

  // Waits for the workers and fills the textures' texels; the first image that failed (in
  // first-use order) is the error.
  void finish() override {
    join();
    std::map<int, size_t> slot;
    for (size_t i = 0; i < images_.size(); ++i) {
      if (!raw_[i].error.empty()) ctx_.fail(index_path("images", size_t(images_[i])), raw_[i].error);
      slot[images_[i]] = i;
    }
    std::map<std::pair<int, bool>, std::shared_ptr<const std::vector<uint32_t>>> floats;
    for (const auto& r : requests_) {
      Raw& d = raw_[slot[r.image]];
      Texture& tex = out_[r.texture];
      tex.width = d.width, tex.height = d.height;
      if (!d.sixteen) {
        tex.words = d.words;
        tex.format = r.srgb ? TexelFormat::Rgba8Srgb : TexelFormat::Rgba8Unorm;
        continue;
      }
      auto& f = floats[{r.image, r.srgb}];
      if (!f) {
        auto words = std::make_shared<std::vector<uint32_t>>(d.sixteen_bit.size());
        for (size_t i = 0; i < words->size(); ++i) {
          const float c = d.sixteen_bit[i] / 65535.0f;
          (*words)[i] = std::bit_cast<uint32_t>(r.srgb && i % 4 != 3 ? srgb_to_linear(c) : c);
        }
        f = std::move(words);
      }
      tex.words = f, tex.format = TexelFormat::Rgba32F;
    }
    for (const auto& j : derived_jobs_) make_roughness(j);
    raw_.clear();
  }

  ~TextureTable() override { join(); }  // an error elsewhere in the file: the workers still finish first

 private:
  struct Header {
    int width = 0, height = 0;
    bool sixteen = false;
  };
  // An image decoded by one worker: 8-bit texels as words (R in the low byte), or 16-bit
  // channels as they are; `error` says why not.
  struct Raw {
    int width = 0, height = 0;
    bool sixteen = false;
    std::shared_ptr<const std::vector<uint32_t>> words;
    std::vector<uint16_t> sixteen_bit;
    std::string error;
  };
  struct DerivedJob {
    size_t texture, source;
    double glossiness_factor;
    std::string field;
  };

  // Adds a texture's bytes to the scene's, which may hold at most kMaxTextureBytes.
  void count_bytes(int64_t bytes, const std::string& field) {
    total_bytes_ += bytes;
    if (total_bytes_ > kMaxTextureBytes)
      ctx_.fail(field, "the scene's textures decode to more than " + std::to_string(kMaxTextureBytes >> 20) + " MiB in all; too large");
  }

  Wrap wrap(int mode, const std::string& field) const {
    switch (mode) {
      case TINYGLTF_TEXTURE_WRAP_REPEAT: return Wrap::Repeat;
      case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Wrap::ClampToEdge;
      case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Wrap::MirroredRepeat;
      default: ctx_.fail(field, "is " + std::to_string(mode) + "; expected 10497 (REPEAT), 33071 (CLAMP_TO_EDGE) or 33648 (MIRRORED_REPEAT)");
    }
  }

  void join() {
    for (auto& w : workers_)
      if (w.joinable()) w.join();
  }

  // The image's size and depth from its header, refused before decoding when too large.
  Header header(int image) const {
    const std::string where = index_path("images", size_t(image));
    const auto& bytes = doc_.encoded_images.at(size_t(image));
    if (bytes.empty()) ctx_.fail(where, "no image data (missing file, empty data or unreadable buffer view)");
    if (bytes.size() > size_t(INT32_MAX)) ctx_.fail(where, "image data over 2 GiB");
    const int n = int(bytes.size());
    Header h;
    int comp = 0;
    if (!stbi_info_from_memory(bytes.data(), n, &h.width, &h.height, &comp)) {
      const std::string what = stand_in(bytes);
      ctx_.fail(where, (what.empty() ? "cannot decode the image (" + decode_failure() + ")" : what) + "; expected a PNG or JPEG file");
    }
    if (h.width < 1 || h.height < 1 || h.width > kMaxImageSide || h.height > kMaxImageSide || int64_t(h.width) * h.height > kMaxImageTexels)
      ctx_.fail(where, std::to_string(h.width) + "x" + std::to_string(h.height) + " image; expected sides of 1 to " + std::to_string(kMaxImageSide) +
                           " pixels and at most " + std::to_string(kMaxImageTexels) + " pixels in all");
    h.sixteen = stbi_is_16_bit_from_memory(bytes.data(), n) != 0;
    return h;
  }

  // Decodes one image (on a worker thread: no throwing, stb_image's failure reason is
  // thread-local).
  Raw decode(int image, const Header& h) const {
    const auto& bytes = doc_.encoded_images[size_t(image)];
    const int n = int(bytes.size());
    Raw r;
    r.width = h.width, r.height = h.height, r.sixteen = h.sixteen;
    const size_t texels = size_t(h.width) * size_t(h.height);
    if (is_png(bytes)) {
      std::vector<uint16_t> sixteen_bit;
      auto words = std::make_shared<std::vector<uint32_t>>();
      if (decode_png(bytes, h.width, h.height, words.get(), h.sixteen ? &sixteen_bit : nullptr).empty()) {
        if (h.sixteen) r.sixteen_bit = std::move(sixteen_bit);
        else r.words = std::move(words);
        return r;
      }
      // Else stb_image, which accepts some damaged files that libpng refuses.
    }
    int dw = 0, dh = 0, comp = 0;
    if (h.sixteen) {
      std::unique_ptr<stbi_us, void (*)(void*)> px(stbi_load_16_from_memory(bytes.data(), n, &dw, &dh, &comp, 4), stbi_image_free);
      if (!px || dw != h.width || dh != h.height) return r.error = "cannot decode the image (" + decode_failure() + ")", r;
      r.sixteen_bit.assign(px.get(), px.get() + 4 * texels);
    } else {
      std::unique_ptr<stbi_uc, void (*)(void*)> px(stbi_load_from_memory(bytes.data(), n, &dw, &dh, &comp, 4), stbi_image_free);
      if (!px || dw != h.width || dh != h.height) return r.error = "cannot decode the image (" + decode_failure() + ")", r;
      auto words = std::make_shared<std::vector<uint32_t>>(texels);
      const stbi_uc* p = px.get();
      for (size_t i = 0; i < texels; ++i)
        (*words)[i] = uint32_t(p[4 * i]) | uint32_t(p[4 * i + 1]) << 8 | uint32_t(p[4 * i + 2]) << 16 | uint32_t(p[4 * i + 3]) << 24;
      r.words = std::move(words);
    }
    return r;
  }

  // G = roughness = 1 - glossiness_factor x A (roughness_from_glossiness). 8-bit texels stay
  // 8-bit when the factor is 1 (G = 255 - A exactly); otherwise the texels are float.
  void make_roughness(const DerivedJob& j) {
    const Texture& source = out_[j.source];
    Texture& tex = out_[j.texture];
    tex.width = source.width, tex.height = source.height;
    const size_t texels = size_t(tex.width) * size_t(tex.height);
    auto words = std::make_shared<std::vector<uint32_t>>();
    if (source.format == TexelFormat::Rgba8Unorm && j.glossiness_factor == 1.0) {
      words->reserve(texels);
      for (uint32_t w : *source.words) words->push_back((255u - (w >> 24)) << 8 | 255u << 16 | 255u << 24);
      tex.format = TexelFormat::Rgba8Unorm;
    } else {
      words->reserve(4 * texels);
      for (int y = 0; y < source.height; ++y)
        for (int x = 0; x < source.width; ++x) {
          const float roughness = std::clamp(1.0f - float(j.glossiness_factor) * source.texel(x, y).a, 0.0f, 1.0f);
          for (float c : {0.0f, roughness, 1.0f, 1.0f}) words->push_back(std::bit_cast<uint32_t>(c));
        }
      tex.format = TexelFormat::Rgba32F;
    }
    count_bytes(int64_t(words->size() * sizeof(uint32_t)), j.field);
    tex.words = std::move(words);
  }

  const Context& ctx_;
  const Document& doc_;
  std::vector<Texture>& out_;
  std::map<std::tuple<int, int, bool>, int> index_;
  std::map<std::pair<int, double>, int> derived_;  // (source texture, glossiness factor) -> texture
  struct Request {
    size_t texture;
    int image;
    bool srgb;
  };
  std::vector<Request> requests_;  // textures whose texels finish() decodes
  std::vector<DerivedJob> derived_jobs_;
  std::set<std::pair<int, bool>> counted_;  // (image, colour space) whose bytes are counted
  int64_t total_bytes_ = 0;
  // Decoding (start, finish): images in first-use order, their headers, the workers' results.
  std::vector<int> images_;
  std::map<int, Header> headers_;
  std::vector<Raw> raw_;
  std::atomic<size_t> next_{0};
  std::vector<std::thread> workers_;
};

double number(const Context& ctx, const tinygltf::Value& v, const std::string& field, double lo, double hi) {
  if (!v.IsNumber()) ctx.fail(field, "must be a number");
  const double x = v.GetNumberAsDouble();
  if (!(x >= lo && x <= hi)) ctx.fail(field, "is " + std::to_string(x) + "; expected a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return x;
}

// An extension's array of N numbers in [lo, hi] (`field` names it; components as field[k]).
template <int N>
glm::vec<N, float> numbers(const Context& ctx, const tinygltf::Value& a, const std::string& field, double lo, double hi) {
  if (!a.IsArray() || a.ArrayLen() != N) ctx.fail(field, "expected an array of " + std::to_string(N) + " numbers");
  glm::vec<N, float> v;
  for (int k = 0; k < N; ++k) v[k] = float(number(ctx, a.Get(k), field + "[" + std::to_string(k) + "]", lo, hi));
  return v;
}

glm::vec3 color3(const Context& ctx, const std::vector<double>& v, const std::string& field, double hi) {
  if (v.size() != 3) ctx.fail(field, "has " + std::to_string(v.size()) + " components; expected 3");
  for (double x : v)
    if (!(x >= 0.0 && x <= hi)) ctx.fail(field, "component " + std::to_string(x) + " is outside [0, " + std::to_string(hi) + "]");
  return glm::vec3(float(v[0]), float(v[1]), float(v[2]));
}

// KHR_texture_transform on a textureInfo: (u, v) -> offset + R(rotation) * scale * (u, v), with
// R = [cos sin; -sin cos] (the extension's GLSL, ratified version; its example maps the unit
// square onto the lower-left quadrant rotated clockwise, which fixes the sign).
glm::dmat3 texture_transform(const Context& ctx, const tinygltf::Value& e, const std::string& field, int& set) {
  if (!e.IsObject()) ctx.fail(field, "must be a JSON object");
  auto pair = [&](const char* key, glm::dvec2 fallback) {
    return e.Has(key) ? glm::dvec2(numbers<2>(ctx, e.Get(key), field + "." + key, -1e30, 1e30)) : fallback;
  };
  const glm::dvec2 offset = pair("offset", glm::dvec2(0.0)), scale = pair("scale", glm::dvec2(1.0));
  const double r = e.Has("rotation") ? number(ctx, e.Get("rotation"), field + ".rotation", -1e30, 1e30) : 0.0;
  if (e.Has("texCoord")) {
    if (!e.Get("texCoord").IsInt() || e.Get("texCoord").GetNumberAsInt() < 0) ctx.fail(field + ".texCoord", "must be a non-negative integer");
    set = e.Get("texCoord").GetNumberAsInt();  // overrides the textureInfo's own (the extension's texCoord)
  }
  const double c = std::cos(r), s = std::sin(r);
  const glm::dmat3 T(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1), R(c, -s, 0, s, c, 0, 0, 0, 1), S(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  return T * R * S;
}

// Reads a textureInfo's texture-coordinate set and transform into the material's mappings
// (UvMapping): renderers keep two per vertex (Mesh::uvs, Mesh::uvs2), which covers glTF's
// TEXCOORD_1 for some slots and per-texture KHR_texture_transform as real assets use them.
class UvTable {
 public:
  UvTable(const Context& ctx, Material& material, std::vector<UvMapping>& out) : ctx_(ctx), material_(material), out_(out) {}

  // The texture in `slot` reads this mapping.
  void use(TextureSlot slot, int tex_coord, const tinygltf::Value* transform, const std::string& field) {
    if (tex_coord < 0) ctx_.fail(field + ".texCoord", "is " + std::to_string(tex_coord) + "; expected a non-negative integer");
    UvMapping m;
    m.set = tex_coord;
    m.field = field;
    if (transform) m.transform = texture_transform(ctx_, *transform, field + ".extensions.KHR_texture_transform", m.set);
    size_t k = 0;
    while (k < out_.size() && (out_[k].set != m.set || out_[k].transform != m.transform)) ++k;
    if (k == out_.size()) {
      if (out_.size() == 2) {
        auto says = [](const UvMapping& u) {
          return "TEXCOORD_" + std::to_string(u.set) + (u.transform != glm::dmat3(1.0) ? " with a texture transform" : "");
        };
        ctx_.fail(field, "reads " + says(m) + ", unlike " + out_[0].field + " (" + says(out_[0]) + ") and " + out_[1].field + " (" +
                             says(out_[1]) + "); giq applies at most two texture-coordinate mappings (set and transform) per material");
      }
      out_.push_back(m);
    }
    same_as(slot, k == 1);
  }
  // A core textureInfo (tinygltf's TextureInfo / NormalTextureInfo).
  template <class Info>
  void use(TextureSlot slot, const Info& info, const std::string& field) {
    auto it = info.extensions.find("KHR_texture_transform");
    use(slot, info.texCoord, it == info.extensions.end() ? nullptr : &it->second, field);
  }
  // The texture in `slot` reads the mapping `second` says.
  void same_as(TextureSlot slot, bool second) {
    material_.uv2_slots = second ? material_.uv2_slots | slot : material_.uv2_slots & ~uint32_t(slot);
  }

 private:
  const Context& ctx_;
  Material& material_;
  std::vector<UvMapping>& out_;
};

// A textureInfo given as an extension's JSON value (KHR_materials_specular textures).
int extension_texture(const Context& ctx, TextureTable& table, UvTable& uv, TextureSlot slot, const tinygltf::Value& info, const std::string& field,
                      bool srgb) {
  if (!info.IsObject() || !info.Has("index") || !info.Get("index").IsInt()) ctx.fail(field + ".index", "missing or not an integer");
  int tex_coord = 0;
  if (info.Has("texCoord")) {
    if (!info.Get("texCoord").IsInt()) ctx.fail(field + ".texCoord", "must be an integer");
    tex_coord = info.Get("texCoord").GetNumberAsInt();
  }
  const tinygltf::Value* transform = nullptr;
  if (info.Has("extensions") && info.Get("extensions").Has("KHR_texture_transform")) transform = &info.Get("extensions").Get("KHR_texture_transform");
  uv.use(slot, tex_coord, transform, field);
  return table.use(info.Get("index").GetNumberAsInt(), field, srgb);
}

}  // namespace

std::unique_ptr<TextureDecoding> load_materials(const Context& ctx, const Document& doc, std::vector<Material>& materials,
                                                std::vector<Texture>& textures, std::vector<std::vector<UvMapping>>& uv_mappings) {
  auto decoding = std::make_unique<TextureTable>(ctx, doc, textures);
  TextureTable& table = *decoding;
  const auto& m = ctx.model;
  for (size_t i = 0; i < m.materials.size(); ++i) {
    const auto& g = m.materials[i];
    const std::string where = index_path("materials", i);
    Material mat;
    std::vector<UvMapping> mappings;
    UvTable uv(ctx, mat, mappings);
    mat.name = g.name.empty() ? "material" + std::to_string(i) : g.name;
    const auto& pbr = g.pbrMetallicRoughness;
    const std::string pw = where + ".pbrMetallicRoughness";
    if (pbr.baseColorFactor.size() != 4) ctx.fail(pw + ".baseColorFactor", "has " + std::to_string(pbr.baseColorFactor.size()) + " components; expected 4");
    for (int c = 0; c < 4; ++c) {
      const double x = pbr.baseColorFactor[size_t(c)];
      if (!(x >= 0.0 && x <= 1.0)) ctx.fail(pw + ".baseColorFactor", "component " + std::to_string(x) + " is outside [0, 1]");
      mat.base_color[c] = float(x);
    }
    mat.metallic = float(number(ctx, tinygltf::Value(pbr.metallicFactor), pw + ".metallicFactor", 0.0, 1.0));
    mat.roughness = float(number(ctx, tinygltf::Value(pbr.roughnessFactor), pw + ".roughnessFactor", 0.0, 1.0));
    if (pbr.baseColorTexture.index >= 0) {
      uv.use(kBaseColorSlot, pbr.baseColorTexture, pw + ".baseColorTexture");
      mat.base_color_texture = table.use(pbr.baseColorTexture.index, pw + ".baseColorTexture", true);
    }
    if (pbr.metallicRoughnessTexture.index >= 0) {
      uv.use(kMetallicRoughnessSlot, pbr.metallicRoughnessTexture, pw + ".metallicRoughnessTexture");
      mat.metallic_roughness_texture = table.use(pbr.metallicRoughnessTexture.index, pw + ".metallicRoughnessTexture", false);
    }
    if (g.normalTexture.index >= 0) {
      uv.use(kNormalSlot, g.normalTexture, where + ".normalTexture");
      mat.normal_texture = table.use(g.normalTexture.index, where + ".normalTexture", false);
      mat.normal_scale = float(number(ctx, tinygltf::Value(g.normalTexture.scale), where + ".normalTexture.scale", -1e6, 1e6));
    }
    mat.emissive = color3(ctx, g.emissiveFactor, where + ".emissiveFactor", 1.0);
    if (g.emissiveTexture.index >= 0) {
      uv.use(kEmissiveSlot, g.emissiveTexture, where + ".emissiveTexture");
      mat.emissive_texture = table.use(g.emissiveTexture.index, where + ".emissiveTexture", true);
    }
    if (g.alphaMode == "MASK") {
      mat.alpha_mode = AlphaMode::Mask;
    } else if (g.alphaMode == "BLEND") {
      mat.alpha_mode = AlphaMode::Blend;  // stochastic transparency (AlphaMode)
    } else if (g.alphaMode != "OPAQUE") {
      ctx.fail(where + ".alphaMode", "is \"" + g.alphaMode + "\"; expected OPAQUE, MASK or BLEND");
    }
    mat.alpha_cutoff = float(number(ctx, tinygltf::Value(g.alphaCutoff), where + ".alphaCutoff", 0.0, 1e6));
    mat.double_sided = g.doubleSided;

    if (auto it = g.extensions.find("KHR_materials_emissive_strength"); it != g.extensions.end()) {
      const std::string ew = where + ".extensions.KHR_materials_emissive_strength";
      if (it->second.Has("emissiveStrength"))
        mat.emissive *= float(number(ctx, it->second.Get("emissiveStrength"), ew + ".emissiveStrength", 0.0, 1e30));
    }
    if (auto it = g.extensions.find("KHR_materials_specular"); it != g.extensions.end()) {
      const std::string sw = where + ".extensions.KHR_materials_specular";
      const auto& e = it->second;
      if (e.Has("specularFactor")) mat.specular = float(number(ctx, e.Get("specularFactor"), sw + ".specularFactor", 0.0, 1.0));
      if (e.Has("specularColorFactor")) mat.specular_color = numbers<3>(ctx, e.Get("specularColorFactor"), sw + ".specularColorFactor", 0.0, 1e6);
      if (e.Has("specularTexture")) mat.specular_texture = extension_texture(ctx, table, uv, kSpecularSlot, e.Get("specularTexture"), sw + ".specularTexture", false);
      if (e.Has("specularColorTexture"))
        mat.specular_color_texture = extension_texture(ctx, table, uv, kSpecularColorSlot, e.Get("specularColorTexture"), sw + ".specularColorTexture", true);
    }
    if (auto it = g.extensions.find("KHR_materials_pbrSpecularGlossiness"); it != g.extensions.end()) {
      // Converted as glTF-Transform's metalRough() does: a dielectric whose F0 is the specular
      // colour (KHR_materials_specular with specular 1; renderers take min(0.04 x
      // specular_color, 1), hence the 1/0.04), whose base colour is the diffuse colour and whose
      // roughness is 1 - glossiness. What differs: the spec-gloss model weighs diffuse by
      // 1 - max(specular), giq's dielectric by 1 - max(Fresnel), which is the same at normal
      // incidence and less towards grazing angles.
      const std::string xw = where + ".extensions.KHR_materials_pbrSpecularGlossiness";
      const auto& e = it->second;
      if (!e.IsObject()) ctx.fail(xw, "must be a JSON object");
      mat.base_color = glm::vec4(1.0f), mat.base_color_texture = -1;
      if (e.Has("diffuseFactor")) mat.base_color = numbers<4>(ctx, e.Get("diffuseFactor"), xw + ".diffuseFactor", 0.0, 1.0);
      if (e.Has("diffuseTexture")) mat.base_color_texture = extension_texture(ctx, table, uv, kBaseColorSlot, e.Get("diffuseTexture"), xw + ".diffuseTexture", true);
      const glm::vec3 specular = e.Has("specularFactor") ? numbers<3>(ctx, e.Get("specularFactor"), xw + ".specularFactor", 0.0, 1.0) : glm::vec3(1.0f);
      const double glossiness = e.Has("glossinessFactor") ? number(ctx, e.Get("glossinessFactor"), xw + ".glossinessFactor", 0.0, 1.0) : 1.0;
      mat.metallic = 0.0f, mat.metallic_roughness_texture = -1;
      mat.roughness = float(1.0 - glossiness);
      mat.specular = 1.0f, mat.specular_texture = -1, mat.specular_color_texture = -1;
      mat.specular_color = specular / 0.04f;
      if (e.Has("specularGlossinessTexture")) {
        const std::string tw = xw + ".specularGlossinessTexture";
        mat.specular_color_texture = extension_texture(ctx, table, uv, kSpecularColorSlot, e.Get("specularGlossinessTexture"), tw, true);
        uv.same_as(kMetallicRoughnessSlot, mat.uv2_slots & kSpecularColorSlot);
        mat.metallic_roughness_texture = table.roughness_from_glossiness(e.Get("specularGlossinessTexture").Get("index").GetNumberAsInt(), tw, glossiness);
        mat.roughness = 1.0f;  // the texture holds 1 - glossiness x A
      }
      ctx.warn("KHR_materials_pbrSpecularGlossiness",
               xw + ": converted to metallic-roughness (F0 = the specular colour, roughness = 1 - glossiness); diffuse is weighted by "
                    "1 - Fresnel instead of 1 - max(specular)");
    }
    if (auto it = g.extensions.find("KHR_materials_ior"); it != g.extensions.end() && it->second.Has("ior")) {
      // F0 = min(((ior - 1) / (ior + 1))^2 x specularColor, 1) x specular (KHR_materials_ior,
      // KHR_materials_specular); renderers evaluate min(0.04 x specular_color, 1) x specular,
      // so the ratio to the default ior 1.5 (F0 0.04) folds into specular_color exactly.
      const std::string field = where + ".extensions.KHR_materials_ior.ior";
      const double ior = number(ctx, it->second.Get("ior"), field, 0.0, 1e6);
      if (ior > 0.0 && ior < 1.0) ctx.fail(field, "is " + std::to_string(ior) + "; expected 0 or at least 1");
      const double f0 = std::pow((ior - 1.0) / (ior + 1.0), 2.0);
      mat.specular_color *= float(f0 / 0.04);
    }
    if (g.extensions.count("KHR_materials_unlit")) {
      // Unlit: the surface shows its base colour whatever the light (KHR_materials_unlit). In a
      // light transport simulation that is a surface that emits its base colour and reflects
      // nothing: base colour (factor x texture) becomes the emission, and the reflectance goes
      // to zero while alpha (for MASK) stays.
      mat.emissive = glm::vec3(mat.base_color);
      mat.emissive_texture = mat.base_color_texture >= 0 ? table.use(pbr.baseColorTexture.index, pw + ".baseColorTexture", true) : -1;
      uv.same_as(kEmissiveSlot, mat.uv2_slots & kBaseColorSlot);
      mat.base_color = glm::vec4(0.0f, 0.0f, 0.0f, mat.base_color.a);
      mat.metallic = 0.0f, mat.metallic_roughness_texture = -1;
      mat.specular = 0.0f, mat.specular_texture = -1, mat.specular_color_texture = -1;
      mat.normal_texture = -1;
    }
    materials.push_back(std::move(mat));
    uv_mappings.push_back(std::move(mappings));
  }
  table.start();
  return decoding;
}

}  // namespace giq::scenes::gltf
