# Writes blender_tangents.glb: normal-mapped meshes whose TANGENT attribute Blender's own glTF
# exporter computed (MikkTSpace), for tests/scenes/tangent_space_test.cpp, which strips the
# attribute and checks that giq's tangents (scenes/src/tangent_space.h) are Blender's. Runs
# inside Blender (3.4, Debian's package: tools/bootstrap --with-blender):
#
#   blender -b --factory-startup --python-exit-code 2 --python tests/data/scenes/blender_tangents.py
#
# The meshes, smooth shaded, each with its own node:
# - Suzanne (curved, small and large triangles, UV islands with seams);
# - a UV sphere (poles where many triangles meet at one vertex, a UV seam at u = 0);
# - a wavy 8 x 8 grid whose UVs are sheared and stretched (dp/du not perpendicular to dp/dv),
#   its left half mirrored in u and squeezed to half the scale.

import math
import os

import bmesh
import bpy

HERE = os.path.dirname(os.path.abspath(__file__))

bpy.ops.wm.read_factory_settings(use_empty=True)

material = bpy.data.materials.new("normal_mapped")
material.use_nodes = True
nodes = material.node_tree.nodes
image = bpy.data.images.new("flat_normal", 4, 4)
image.pixels = [0.5, 0.5, 1.0, 1.0] * 16
texture = nodes.new("ShaderNodeTexImage")
texture.image = image
normal_map = nodes.new("ShaderNodeNormalMap")
material.node_tree.links.new(texture.outputs["Color"], normal_map.inputs["Color"])
material.node_tree.links.new(normal_map.outputs["Normal"], nodes["Principled BSDF"].inputs["Normal"])


def finish(obj, location):
    # Triangulated here, so that Blender's MikkTSpace sees the triangles the file will hold:
    # given a quad, MikkTSpace forces both its triangles to one UV orientation (the larger
    # one's), which a reader of the file's triangles cannot know.
    mesh = bmesh.new()
    mesh.from_mesh(obj.data)
    bmesh.ops.triangulate(mesh, faces=mesh.faces[:])
    mesh.to_mesh(obj.data)
    mesh.free()
    obj.location = location
    obj.data.materials.append(material)
    for p in obj.data.polygons:
        p.use_smooth = True


bpy.ops.mesh.primitive_monkey_add(size=1.0, calc_uvs=True)
finish(bpy.context.active_object, (0.0, 0.0, 0.0))

bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8, radius=0.8, calc_uvs=True)
finish(bpy.context.active_object, (2.5, 0.0, 0.0))

N = 8
verts, faces = [], []
for j in range(N + 1):
    for i in range(N + 1):
        x, y = i / N * 2.0 - 1.0, j / N * 2.0 - 1.0
        verts.append((x, y, 0.3 * math.sin(2.0 * x) * math.cos(1.5 * y)))
for j in range(N):
    for i in range(N):
        a = j * (N + 1) + i
        faces.append((a, a + 1, a + N + 2, a + N + 1))
grid = bpy.data.meshes.new("grid")
grid.from_pydata(verts, [], faces)
uv = grid.uv_layers.new(name="UVMap")
for loop in grid.loops:
    x, y, _ = verts[loop.vertex_index]
    u = x if x > 0.0 else -x * 0.5
    uv.data[loop.index].uv = (u + 0.4 * y, 0.7 * y)
obj = bpy.data.objects.new("grid", grid)
bpy.context.scene.collection.objects.link(obj)
finish(obj, (-2.5, 0.0, 0.0))

bpy.ops.export_scene.gltf(filepath=os.path.join(HERE, "blender_tangents.glb"), export_format="GLB",
                          export_tangents=True, export_normals=True, export_texcoords=True,
                          export_materials="EXPORT", export_apply=True)
