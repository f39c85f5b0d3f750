#pragma once
// A glTF texture decoded once at load time into linear float RGBA.

#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace giq::scenes {

enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };
enum class Filter { Nearest, Linear };

struct Texture {
  std::string name;  // image name or URI, for messages
  int width = 0;
  int height = 0;
  // Row-major, first row = v 0 (glTF puts UV (0,0) at the image's top-left corner).
  // Linear: colour textures (base colour, emissive, specular colour) are decoded from sRGB;
  // data textures (metallic-roughness, normal, specular) are stored as read. Shared, so
  // posing a scene at another time does not copy texels.
  std::shared_ptr<const std::vector<glm::vec4>> texels;
  Wrap wrap_s = Wrap::Repeat;
  Wrap wrap_t = Wrap::Repeat;
  Filter filter = Filter::Linear;  // magnification filter; minification is not mip-mapped

  // Filtered lookup following the sampler's wrap modes; texel centres at (i + 0.5) / size.
  glm::vec4 sample(glm::vec2 uv) const;
};

}  // namespace giq::scenes
