#include "gltf_draco.h"

#include <draco/compression/decode.h>

#include <algorithm>
#include <cstring>
#include <vector>

namespace giq::scenes::gltf {
namespace {

constexpr const char* kExtension = "KHR_draco_mesh_compression";

// One component of a decoded Draco value, normalised as glTF normalises the accessor's
// integers (glTF 2.0 spec, 3.11: c/255, max(c/127, -1), c/65535, max(c/32767, -1)).
double component(const unsigned char* p, draco::DataType t, bool normalized) {
  auto get = [&](auto v) {
    std::memcpy(&v, p, sizeof v);
    return v;
  };
  switch (t) {
    case draco::DT_INT8: { const double c = get(int8_t{}); return normalized ? std::max(c / 127.0, -1.0) : c; }
    case draco::DT_UINT8: { const double c = get(uint8_t{}); return normalized ? c / 255.0 : c; }
    case draco::DT_INT16: { const double c = get(int16_t{}); return normalized ? std::max(c / 32767.0, -1.0) : c; }
    case draco::DT_UINT16: { const double c = get(uint16_t{}); return normalized ? c / 65535.0 : c; }
    case draco::DT_INT32: return double(get(int32_t{}));
    case draco::DT_UINT32: return double(get(uint32_t{}));
    case draco::DT_FLOAT32: return double(get(float{}));
    case draco::DT_FLOAT64: return get(double{});
    default: return 0.0;  // refused before (data types checked per attribute)
  }
}

}  // namespace

void decode_draco_primitive(const Context& ctx, const tinygltf::Primitive& p, const std::string& w) {
  ctx.decoded_accessors.clear();
  const auto it = p.extensions.find(kExtension);
  if (it == p.extensions.end()) return;
  const std::string ew = w + ".extensions." + kExtension;
  const tinygltf::Value& e = it->second;
  if (!e.IsObject()) ctx.fail(ew, "must be a JSON object");
  if (!e.Has("bufferView") || !e.Get("bufferView").IsInt()) ctx.fail(ew + ".bufferView", "missing or not a buffer view index");
  if (!e.Has("attributes") || !e.Get("attributes").IsObject()) ctx.fail(ew + ".attributes", "missing or not an object");

  const int view = e.Get("bufferView").GetNumberAsInt();
  const auto& m = ctx.model;
  if (view < 0 || size_t(view) >= m.bufferViews.size())
    ctx.fail(ew + ".bufferView", "is " + std::to_string(view) + "; the file has " + std::to_string(m.bufferViews.size()) + " buffer views");
  const auto& bv = m.bufferViews[size_t(view)];
  const unsigned char* bytes = nullptr;
  size_t size = 0;
  if (auto d = ctx.decoded_views.find(view); d != ctx.decoded_views.end()) {
    bytes = d->second.data(), size = d->second.size();
  } else {
    if (bv.buffer < 0 || size_t(bv.buffer) >= m.buffers.size()) ctx.fail(index_path("bufferViews", size_t(view)) + ".buffer", "names no buffer of the file");
    const auto& data = m.buffers[size_t(bv.buffer)].data;
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
      ctx.fail(index_path("bufferViews", size_t(view)), "exceeds its buffer of " + std::to_string(data.size()) + " bytes");
    bytes = data.data() + bv.byteOffset, size = bv.byteLength;
  }

  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes), size);
  const auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok() || type.value() != draco::TRIANGULAR_MESH)
    ctx.fail(ew + ".bufferView", "does not hold a Draco triangle mesh" + (type.ok() ? std::string() : ": " + type.status().error_msg_string()));
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) ctx.fail(ew + ".bufferView", "the Draco data does not decode: " + decoded.status().error_msg_string());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  const size_t points = mesh->num_points();

  // Indices: the decoded faces, which refer to the decoded points.
  if (p.indices >= 0) {
    AccessorData idx;
    idx.components = 1;
    idx.count = size_t(mesh->num_faces()) * 3;
    idx.values.reserve(idx.count);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = mesh->face(f)[k].value();
        if (v >= points) ctx.fail(ew + ".bufferView", "the Draco data has a face corner beyond its " + std::to_string(points) + " points");
        idx.values.push_back(double(v));
      }
    ctx.decoded_accessors[p.indices] = std::move(idx);
  }

  const tinygltf::Value& attrs = e.Get("attributes");
  for (const std::string& name : attrs.Keys()) {
    const std::string aw = ew + ".attributes." + name;
    const auto a = p.attributes.find(name);
    if (a == p.attributes.end()) ctx.fail(aw, "names an attribute the primitive does not have; expected one of its attributes");
    if (!attrs.Get(name).IsInt()) ctx.fail(aw, "must be a Draco attribute id");
    const int id = attrs.Get(name).GetNumberAsInt();
    const draco::PointAttribute* att = id >= 0 ? mesh->GetAttributeByUniqueId(uint32_t(id)) : nullptr;
    if (!att) ctx.fail(aw, "is " + std::to_string(id) + "; the Draco data has no attribute with that id");
    const draco::DataType t = att->data_type();
    if (t == draco::DT_INVALID || t == draco::DT_INT64 || t == draco::DT_UINT64 || t == draco::DT_BOOL || t >= draco::DT_TYPES_COUNT)
      ctx.fail(aw, "decodes to a Draco data type glTF has no component type for");
    if (a->second < 0 || size_t(a->second) >= m.accessors.size()) ctx.fail(w + ".attributes." + name, "names no accessor of the file");
    const tinygltf::Accessor& acc = m.accessors[size_t(a->second)];
    const int comps = att->num_components();
    const size_t csize = size_t(draco::DataTypeLength(t));
    if (comps < 1 || comps > 4 || size_t(att->byte_stride()) < size_t(comps) * csize)
      ctx.fail(aw, "decodes to " + std::to_string(comps) + " components per value; expected 1 to 4");
    AccessorData out;
    out.components = comps;
    out.count = points;
    out.values.resize(points * size_t(comps));
    std::vector<unsigned char> value(size_t(att->byte_stride()));
    for (draco::PointIndex i(0); i < uint32_t(points); ++i) {
      const draco::AttributeValueIndex v = att->mapped_index(i);
      if (v.value() >= att->size()) ctx.fail(aw, "the Draco data maps a point to a value it does not have");
      att->GetValue(v, value.data());
      for (int c = 0; c < comps; ++c)
        out.values[size_t(i.value()) * comps + c] = component(value.data() + size_t(c) * csize, t, acc.normalized);
    }
    ctx.decoded_accessors[a->second] = std::move(out);
  }
}

}  // namespace giq::scenes::gltf
