#pragma once
// What every rendering command (giq reference, giq realtime) does to the scene it is given
// before rendering: load it and print what was dropped or approximated, add the light and the
// camera the command line gives, and refuse a scene without any light, whose every image
// would be black.
//
//   --camera eye=x,y,z target=x,y,z [up=x,y,z] [fov=deg]    world coordinates, vertical fov
//            [hfov=deg] [frame=unity|unreal|.. | handedness=left] [units=cm|..]
//                                                            an engine's frame and units, a
//                                                            horizontal fov at the image's aspect
//   --camera auto [fov=deg]                                  frames the scene's bounds
//   --sun dir=x,y,z illuminance=E [color=r,g,b]              a directional light; dir is the
//                                                            way the light travels
//   --env r,g,b  (or one number)                             constant environment radiance
//   --env FILE                                               equirectangular radiance map

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "giq/image/image.h"
#include "giq/scenes/scene.h"

namespace giq::cli {

// The name of the view --camera adds.
inline constexpr const char* kCameraView = "camera";

struct SceneSetup {
  std::vector<std::string> camera;
  std::vector<std::string> sun;
  std::string env;

  void add_options(CLI::App& cmd);
  bool has_camera() const { return !camera.empty(); }
  // Loads the scene, prints its warnings on stderr, adds --sun, --env and the --camera view
  // (kCameraView; aspect = width / height of the image, for hfov=), then throws InputError
  // when the scene has no light at all.
  scenes::Scene load(const std::filesystem::path& path, double aspect) const;
};

// The camera --camera's arguments describe (one or several words; one quoted argument is split
// at spaces), for an image of aspect width / height; throws InputError (field --camera).
scenes::Camera camera_from_arguments(const std::vector<std::string>& camera, const scenes::Scene& scene, double aspect);

// When every pixel of the image's beauty is 0 (or not finite), prints one warning on stderr
// naming the likely causes (a camera looking away or inside geometry, an engine's frame or
// units not converted, lights blocked) and returns true.
bool warn_if_black(const image::Image& image, const std::string& what);

}  // namespace giq::cli
