#include "gltf_meshopt.h"

#include <meshoptimizer.h>

#include "giq/base/error.h"

namespace giq::scenes::gltf {
namespace {

using nlohmann::json;

enum class Mode { Attributes, Triangles, Indices };
enum class Filter { None, Octahedral, Quaternion, Exponential };

std::string string_property(const Document& d, const json& o, const char* key, const std::string& where, const char* fallback) {
  const json* v = member(o, key);
  if (!v) {
    if (!fallback) throw InputError(d.file, where + "." + key, "missing; expected a string");
    return fallback;
  }
  if (!v->is_string()) throw InputError(d.file, where + "." + key, "is " + v->dump() + "; expected a string");
  return v->get<std::string>();
}

}  // namespace

void decode_meshopt_views(const Document& d, Context& ctx) {
  const json* views = member(d.json, "bufferViews");
  if (!views) return;
  for (size_t i = 0; i < views->size(); ++i) {
    const json* exts = member((*views)[i], "extensions");
    const json* e = exts ? member(*exts, kMeshoptExtension) : nullptr;
    if (!e) continue;
    const std::string view = index_path("bufferViews", i), w = view + ".extensions." + kMeshoptExtension;
    if (!e->is_object()) ctx.fail(w, "must be a JSON object");
    auto fail = [&](const char* key, const std::string& message) { ctx.fail(w + (*key ? std::string(".") + key : ""), message); };

    // The extension's properties and its validity rules (EXT_meshopt_compression, "JSON
    // schema updates"), checked before the decoder sees anything: meshoptimizer asserts
    // rather than returns on most of them.
    const uint64_t buffer = unsigned_property(d, *e, "buffer", w, true);
    const uint64_t offset = unsigned_property(d, *e, "byteOffset", w, false, 0);
    const uint64_t length = unsigned_property(d, *e, "byteLength", w, true);
    const uint64_t stride = unsigned_property(d, *e, "byteStride", w, true);
    const uint64_t count = unsigned_property(d, *e, "count", w, true);
    const std::string mode_name = string_property(d, *e, "mode", w, nullptr);
    const std::string filter_name = string_property(d, *e, "filter", w, "NONE");
    Mode mode{};  // each name sets it or fails (throws), which the compiler cannot see through the lambda
    if (mode_name == "ATTRIBUTES") mode = Mode::Attributes;
    else if (mode_name == "TRIANGLES") mode = Mode::Triangles;
    else if (mode_name == "INDICES") mode = Mode::Indices;
    else fail("mode", "is \"" + mode_name + "\"; expected \"ATTRIBUTES\", \"TRIANGLES\" or \"INDICES\"");
    Filter filter{};
    if (filter_name == "NONE") filter = Filter::None;
    else if (filter_name == "OCTAHEDRAL") filter = Filter::Octahedral;
    else if (filter_name == "QUATERNION") filter = Filter::Quaternion;
    else if (filter_name == "EXPONENTIAL") filter = Filter::Exponential;
    else fail("filter", "is \"" + filter_name + "\"; expected \"NONE\", \"OCTAHEDRAL\", \"QUATERNION\" or \"EXPONENTIAL\"");

    if (buffer >= ctx.model.buffers.size())
      fail("buffer", "is " + std::to_string(buffer) + "; the file has " + std::to_string(ctx.model.buffers.size()) + " buffers");
    if (d.placeholder_buffers[buffer]) fail("buffer", "names buffers[" + std::to_string(buffer) + "], which holds no data; expected the buffer of the compressed bytes");
    const auto& data = ctx.model.buffers[buffer].data;
    if (offset > data.size() || length > data.size() - offset)
      fail("", "bytes [" + std::to_string(offset) + ", " + std::to_string(offset + length) + ") exceed buffers[" + std::to_string(buffer) + "] of " +
                   std::to_string(data.size()) + " bytes");
    if (mode == Mode::Attributes && (stride == 0 || stride % 4 != 0 || stride > 256))
      fail("byteStride", "is " + std::to_string(stride) + "; ATTRIBUTES needs a multiple of 4 up to 256");
    if (mode != Mode::Attributes && stride != 2 && stride != 4)
      fail("byteStride", "is " + std::to_string(stride) + "; " + mode_name + " needs 2 or 4");
    if (mode == Mode::Triangles && count % 3 != 0) fail("count", "is " + std::to_string(count) + "; TRIANGLES needs a multiple of 3");
    if (mode != Mode::Attributes && filter != Filter::None) fail("filter", "is \"" + filter_name + "\"; only ATTRIBUTES may have a filter");
    if (filter == Filter::Octahedral && stride != 4 && stride != 8) fail("byteStride", "is " + std::to_string(stride) + "; OCTAHEDRAL needs 4 or 8");
    if (filter == Filter::Quaternion && stride != 8) fail("byteStride", "is " + std::to_string(stride) + "; QUATERNION needs 8");

    const json& parent = (*views)[i];
    const uint64_t view_length = unsigned_property(d, parent, "byteLength", view, true);
    if (count > (uint64_t(1) << 32) || stride * count != view_length)
      fail("count", std::to_string(count) + " elements of " + std::to_string(stride) + " bytes do not fill " + view + ".byteLength " +
                        std::to_string(view_length) + "; they must be equal");
    const uint64_t parent_stride = unsigned_property(d, parent, "byteStride", view, false, 0);
    if (parent_stride != 0 && parent_stride != stride)
      fail("byteStride", "is " + std::to_string(stride) + " but " + view + ".byteStride is " + std::to_string(parent_stride) + "; they must be equal");
    // No codec expands its input more than 64 times (the attribute codec's densest block
    // spends 2 bits per 16 bytes), so a larger claim cannot decode: refused before a few
    // bytes can demand gigabytes.
    const uint64_t size = stride * count;
    if (size > 64 * length + 4096 || size > (uint64_t(1) << 30))
      fail("count", std::to_string(size) + " bytes cannot come from " + std::to_string(length) + " compressed bytes (at most 64 times as many, and 1 GiB)");

    std::vector<unsigned char> out(size);
    const unsigned char* src = data.data() + offset;
    int rc = 0;
    switch (mode) {
      case Mode::Attributes: rc = meshopt_decodeVertexBuffer(out.data(), count, stride, src, length); break;
      case Mode::Triangles: rc = meshopt_decodeIndexBuffer(out.data(), count, stride, src, length); break;
      case Mode::Indices: rc = meshopt_decodeIndexSequence(out.data(), count, stride, src, length); break;
    }
    if (rc != 0) fail("", "the " + mode_name + " data does not decode (meshoptimizer error " + std::to_string(rc) + "); the file is damaged or uses a newer codec version");
    switch (filter) {
      case Filter::None: break;
      case Filter::Octahedral: meshopt_decodeFilterOct(out.data(), count, stride); break;
      case Filter::Quaternion: meshopt_decodeFilterQuat(out.data(), count, stride); break;
      case Filter::Exponential: meshopt_decodeFilterExp(out.data(), count, stride); break;
    }
    ctx.decoded_views[int(i)] = std::move(out);
  }
}

}  // namespace giq::scenes::gltf
