// Environment radiance as scenes::Scene::environment_radiance: `environment`.rgb is the
// constant radiance, .w the index of the equirectangular map among the scene's textures (-1:
// none). The map's mapping is scenes/environment.h's (+Y up, -Z at the image's centre,
// nearest texels).
#ifndef GIQ_ENVIRONMENT_GLSL
#define GIQ_ENVIRONMENT_GLSL

#include "textures.glsl"

#ifdef GIQ_ENVIRONMENT_MAP
vec2 equirect_uv(vec3 d) {
  const float PI_ = 3.14159265358979;
  return vec2(0.5 + atan(d.x, -d.z) * (0.5 / PI_), acos(clamp(d.y, -1.0, 1.0)) * (1.0 / PI_));
}
#endif

vec3 environment_radiance(vec4 environment, vec3 dir) {
#ifdef GIQ_ENVIRONMENT_MAP
  if (environment.w >= 0.0) return texture_sample(int(environment.w), equirect_uv(dir)).rgb;
#endif
  return environment.rgb;
}

#endif
