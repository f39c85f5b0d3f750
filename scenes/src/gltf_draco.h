#pragma once
// KHR_draco_mesh_compression: a primitive's indices and the attributes it names decoded from
// the Draco bitstream with Debian's libdraco, into Context::decoded_accessors, where
// read_accessor finds them in place of the placeholder accessors.

#include <tiny_gltf.h>

#include <string>

#include "gltf_accessors.h"

namespace giq::scenes::gltf {

// When primitive `p` (at glTF path `w`) carries the extension, decodes it and fills
// ctx.decoded_accessors (replacing what an earlier primitive left there); otherwise clears
// it. Throws InputError naming the field when the extension is malformed or the data does not
// decode.
void decode_draco_primitive(const Context& ctx, const tinygltf::Primitive& p, const std::string& w);

}  // namespace giq::scenes::gltf
