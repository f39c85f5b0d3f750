#pragma once
// A walking figure for the built-in scenes: one skinned mesh of boxes (torso, head, arms,
// legs, feet) over ten joints, and a walk along a circle as rotation and translation keys.
// Where two bones meet (hips, knees, shoulders, waist) the vertices blend their two joints,
// so the skin bends rather than breaks, as a character's does.

#include <string>
#include <vector>

#include "gltf_writer.h"

namespace giq::scenegen {

struct WalkSpec {
  glm::dvec3 centre{0.0};   // of the circle, on the floor
  double radius = 1.0;      // m
  double lap_seconds = 4.0;  // once round, counter-clockwise seen from above
  double stride_seconds = 1.0;  // one step of each foot
  int keys = 120;           // key frames over one lap (the last key closes it)
};

struct Walker {
  int mesh_node = -1;
  std::vector<int> joints;  // the skin's joints; joints[0] is the root that follows the circle
  std::vector<TranslationTrack> translations;
  std::vector<RotationTrack> rotations;
  double speed = 0.0;         // m/s along the circle
  double hip_swing_deg = 0.0, knee_bend_deg = 0.0;
  double height = 0.0;        // m, the head's top at rest
  size_t triangles = 0;
};

// Adds the figure's joint nodes, its skin and its skinned mesh (material `material`) standing
// at the circle's start, and returns the walk's keys (to be put in one animation).
Walker add_walker(GltfWriter& gltf, const WalkSpec& walk, int material);

}  // namespace giq::scenegen
