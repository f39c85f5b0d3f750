#pragma once
// EXT_meshopt_compression: buffer views stored compressed (attribute, triangle and index
// codecs, with the octahedral, quaternion and exponential filters), decoded once after parsing
// into Context::decoded_views, where read_accessor finds them like any other view.

#include "gltf_accessors.h"
#include "gltf_document.h"

namespace giq::scenes::gltf {

// Decodes every compressed view of `doc` into ctx.decoded_views. Throws InputError naming
// the view's extension field when a property breaks the extension's rules or the data does
// not decode.
void decode_meshopt_views(const Document& doc, Context& ctx);

}  // namespace giq::scenes::gltf
