#include "gltf_accessors.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "giq/base/error.h"

namespace giq::scenes::gltf {

void Context::fail(const std::string& field, const std::string& message) const {
  throw InputError(file, field, message);
}

void Context::warn(const std::string& kind, const std::string& message) const {
  for (size_t i = 0; i < warning_kinds_.size(); ++i) {
    Kind& k = warning_kinds_[i];
    if (k.kind != kind) continue;
    warnings[i] = k.message + " (" + std::to_string(++k.count) + " times in the file)";
    return;
  }
  warning_kinds_.push_back({kind, message, 1});
  warnings.push_back(message);
}

std::string index_path(const std::string& array, size_t i) { return array + "[" + std::to_string(i) + "]"; }

namespace {

int component_size(int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT4: return 16;  // inverse bind matrices (FLOAT only: no column padding)
    default: return 0;
  }
}

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown";
  }
}

std::string component_name(int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE (5120)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE (5121)";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT (5122)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT (5123)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT (5125)";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT (5126)";
    default: return std::to_string(ct);
  }
}

// One component as a double; normalized integers map as in glTF 2.0 spec, 3.11
// ("Animations", normalization table): c/255, max(c/127, -1), c/65535, max(c/32767, -1).
double component(const unsigned char* p, int ct, bool normalized) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double c = double(*reinterpret_cast<const int8_t*>(p));
      return normalized ? std::max(c / 127.0, -1.0) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? *p / 255.0 : double(*p);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return double(v);
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return double(v);
    }
  }
}

// The bytes of bufferViews[view] after checking it against its buffer.
std::pair<const unsigned char*, size_t> view_bytes(const Context& ctx, int view, const std::string& field) {
  const auto& m = ctx.model;
  if (view < 0 || size_t(view) >= m.bufferViews.size())
    ctx.fail(field, "is " + std::to_string(view) + "; the file has " + std::to_string(m.bufferViews.size()) + " buffer views");
  if (auto it = ctx.decoded_views.find(view); it != ctx.decoded_views.end()) return {it->second.data(), it->second.size()};
  const auto& bv = m.bufferViews[size_t(view)];
  if (bv.buffer < 0 || size_t(bv.buffer) >= m.buffers.size())
    ctx.fail(index_path("bufferViews", size_t(view)) + ".buffer", "is " + std::to_string(bv.buffer) + "; the file has " + std::to_string(m.buffers.size()) + " buffers");
  const auto& data = m.buffers[size_t(bv.buffer)].data;
  if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
    ctx.fail(index_path("bufferViews", size_t(view)), "bytes [" + std::to_string(bv.byteOffset) + ", " + std::to_string(bv.byteOffset + bv.byteLength) +
                                                          ") exceed buffers[" + std::to_string(bv.buffer) + "] of " + std::to_string(data.size()) + " bytes");
  return {data.data() + bv.byteOffset, bv.byteLength};
}

// Checks that `count` elements of `elem` bytes, `stride` apart from `offset`, fit in `size`.
bool fits(uint64_t offset, uint64_t count, uint64_t stride, uint64_t elem, uint64_t size) {
  if (count == 0) return offset <= size;
  if (offset > size) return false;
  const uint64_t room = size - offset;
  if (elem > room) return false;
  return (count - 1) <= (room - elem) / stride;
}

}  // namespace

AccessorData read_accessor(const Context& ctx, int index, const std::string& field, const AccessorRule& rule) {
  const auto& m = ctx.model;
  if (index < 0 || size_t(index) >= m.accessors.size())
    ctx.fail(field, "is " + std::to_string(index) + "; the file has " + std::to_string(m.accessors.size()) + " accessors");
  const auto& a = m.accessors[size_t(index)];
  const std::string where = index_path("accessors", size_t(index));

  if (std::find(rule.types.begin(), rule.types.end(), a.type) == rule.types.end()) {
    std::string allowed;
    for (int t : rule.types) allowed += std::string(allowed.empty() ? "" : " or ") + type_name(t);
    ctx.fail(where + ".type", std::string("is ") + type_name(a.type) + "; " + field + " needs " + allowed);
  }
  const int ct = a.componentType;
  const bool is_float = ct == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool is_uint = ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                       ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  const bool small_uint = ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  const bool small_sint = ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT;
  const bool accepted = (is_float && rule.float_components && !a.normalized) ||
                        (small_uint && a.normalized && rule.normalized_unsigned) ||
                        (small_sint && a.normalized && rule.normalized_signed) ||
                        (is_uint && !a.normalized && rule.unsigned_integers) ||
                        ((small_uint || small_sint) && !a.normalized && rule.small_integers);
  if (!accepted) {
    std::string allowed;
    auto add = [&](const char* s) { allowed += std::string(allowed.empty() ? "" : ", ") + s; };
    if (rule.float_components) add("FLOAT");
    if (rule.normalized_unsigned) add("normalized UNSIGNED_BYTE/UNSIGNED_SHORT");
    if (rule.normalized_signed) add("normalized BYTE/SHORT");
    if (rule.unsigned_integers) add("UNSIGNED_BYTE/UNSIGNED_SHORT/UNSIGNED_INT");
    if (rule.small_integers) add("BYTE/UNSIGNED_BYTE/SHORT/UNSIGNED_SHORT");
    ctx.fail(where + ".componentType", "is " + std::string(a.normalized ? "normalized " : "") + component_name(ct) + "; " + field + " needs " + allowed);
  }
  const int comps = component_count(a.type);
  const uint64_t csize = uint64_t(component_size(ct));
  const uint64_t elem = uint64_t(comps) * csize;
  if (a.count < 1) ctx.fail(where + ".count", "is 0; expected at least 1");
  // 2^28 elements (several GiB once expanded to doubles) is far beyond any scene giq renders.
  if (a.count > (size_t(1) << 28)) ctx.fail(where + ".count", "is " + std::to_string(a.count) + "; at most 268435456 elements are supported");

  // 2^28 values in all (2 GiB as doubles) is far beyond any scene giq renders.
  constexpr size_t kMaxValues = size_t(1) << 28;
  ctx.values_read += a.count * size_t(comps);
  if (ctx.values_read > kMaxValues)
    ctx.fail(field, "reading " + where + " brings the accessor data read to more than " + std::to_string(kMaxValues) + " values; too large");

  if (auto it = ctx.decoded_accessors.find(index); it != ctx.decoded_accessors.end()) {
    if (a.sparse.isSparse) ctx.fail(where + ".sparse", "is given for an accessor of a Draco-compressed primitive; expected none");
    if (it->second.components != comps)
      ctx.fail(where + ".type", "is " + std::string(type_name(a.type)) + "; the Draco data decodes to elements of " +
                                    std::to_string(it->second.components) + " components");
    // The extension asks that the accessors match the decompressed data, and lets a loader
    // render that data directly; encoders that dedupe or split vertices differently leave
    // counts that do not match (a Rhino exporter's 80004 for 80124). The decoded points and
    // faces are used, with a warning; attributes outside the Draco data (morph targets,
    // uncompressed sets) must still have the decoded count, which the primitive's checks
    // require.
    if (it->second.count != a.count)
      ctx.warn("draco count", where + ".count is " + std::to_string(a.count) + "; the Draco data decodes to " +
                                  std::to_string(it->second.count) + " elements, which are used");
    return it->second;
  }
  AccessorData out;
  out.components = comps;
  out.count = a.count;
  if (a.bufferView < 0) {
    // No bufferView: zeros (spec 3.6.2.3), only useful under sparse substitution. Nothing in
    // the file backs the count, so it is bounded before anything is allocated.
    if (a.count > (size_t(1) << 20)) ctx.fail(where + ".count", "is " + std::to_string(a.count) + " without a bufferView; at most 1048576 elements are supported");
    out.values.assign(a.count * size_t(comps), 0.0);
  } else {
    const auto [bytes, size] = view_bytes(ctx, a.bufferView, where + ".bufferView");
    const auto& bv = m.bufferViews[size_t(a.bufferView)];
    const uint64_t stride = bv.byteStride ? uint64_t(bv.byteStride) : elem;
    if (stride < elem)
      ctx.fail(index_path("bufferViews", size_t(a.bufferView)) + ".byteStride", "is " + std::to_string(stride) + "; " + where + " needs at least its element size " + std::to_string(elem));
    if (!fits(a.byteOffset, a.count, stride, elem, size))
      ctx.fail(where, "byteOffset " + std::to_string(a.byteOffset) + " + " + std::to_string(a.count) + " elements of " + std::to_string(elem) + " bytes (stride " +
                          std::to_string(stride) + ") exceed bufferViews[" + std::to_string(a.bufferView) + "] of " + std::to_string(size) + " bytes");
    out.values.resize(a.count * size_t(comps));
    for (size_t i = 0; i < a.count; ++i)
      for (int c = 0; c < comps; ++c)
        out.values[i * comps + c] = component(bytes + a.byteOffset + i * stride + c * csize, ct, a.normalized);
  }
  if (a.sparse.isSparse) {
    // glTF 2.0 spec, 3.6.2.3 "Sparse Accessors": tightly packed indices (strictly increasing)
    // and values, substituted into the dense data.
    const std::string sp = where + ".sparse";
    if (a.sparse.count < 1 || size_t(a.sparse.count) > a.count)
      ctx.fail(sp + ".count", "is " + std::to_string(a.sparse.count) + "; expected 1 to the accessor's count " + std::to_string(a.count));
    const int ict = a.sparse.indices.componentType;
    if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      ctx.fail(sp + ".indices.componentType", "is " + component_name(ict) + "; expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    const uint64_t n = uint64_t(a.sparse.count);
    const auto [ib, isize] = view_bytes(ctx, a.sparse.indices.bufferView, sp + ".indices.bufferView");
    const auto [vb, vsize] = view_bytes(ctx, a.sparse.values.bufferView, sp + ".values.bufferView");
    const uint64_t isz = uint64_t(component_size(ict));
    if (a.sparse.indices.byteOffset < 0 || !fits(uint64_t(a.sparse.indices.byteOffset), n, isz, isz, isize))
      ctx.fail(sp + ".indices", std::to_string(n) + " indices exceed their buffer view of " + std::to_string(isize) + " bytes");
    if (a.sparse.values.byteOffset < 0 || !fits(uint64_t(a.sparse.values.byteOffset), n, elem, elem, vsize))
      ctx.fail(sp + ".values", std::to_string(n) + " values exceed their buffer view of " + std::to_string(vsize) + " bytes");
    double previous = -1.0;
    for (uint64_t k = 0; k < n; ++k) {
      const double target = component(ib + a.sparse.indices.byteOffset + k * isz, ict, false);
      if (target <= previous || target >= double(a.count))
        ctx.fail(sp + ".indices", "element " + std::to_string(k) + " is " + std::to_string(uint64_t(target)) +
                                      "; indices must increase strictly and stay below the accessor's count " + std::to_string(a.count));
      previous = target;
      for (int c = 0; c < comps; ++c)
        out.values[size_t(target) * comps + c] = component(vb + a.sparse.values.byteOffset + k * elem + c * csize, ct, a.normalized);
    }
  }
  if (is_float)
    for (size_t i = 0; i < out.values.size(); ++i)
      if (!std::isfinite(out.values[i]))
        ctx.fail(where, "element " + std::to_string(i / comps) + " component " + std::to_string(i % comps) + " is " +
                            std::to_string(out.values[i]) + "; expected a finite number");
  return out;
}

}  // namespace giq::scenes::gltf
