#pragma once
// Emitters completed at load (their surface and materials) and their particles as geometry in
// a posed scene (particles.h).

#include <string>
#include <vector>

#include "giq/scenes/scene.h"

namespace giq::scenes {

// The emitting surface of `e` from the meshes of its node in `meshes` (as posed at t = 0),
// and its `stages` materials appended to `materials`. Throws InputError (file, `field`) when
// the node has no triangle with area.
void complete_emitter(Emitter& e, const std::vector<Mesh>& meshes, std::vector<Material>& materials, const std::string& file,
                      const std::string& field);

// The particles alive at time t appended to `meshes`: per emitter, one mesh per stage of life
// (empty when no particle is in it) holding its particle count and, where `detail` places
// them, each particle as an octahedron. Throws InputError when an emitter would have emitted
// more than 2^32 particles by then. `frame` is the sequence's frame duration: where each
// particle was then (Mesh::previous_positions).
void add_particle_meshes(const std::vector<Emitter>& emitters, double t, double frame, ParticleDetail detail,
                         std::vector<Mesh>& meshes, const std::string& file);

}  // namespace giq::scenes
