# Writes blender_figure.glb and blender_figure.json: a skinned, morphing figure exported by
# Blender's own glTF exporter, and the vertex positions Blender itself computes for it at some
# frames, for tests/scenes/deformation_test.cpp. Runs inside Blender (3.4, Debian's package:
# tools/bootstrap --with-blender):
#
#   blender -b --factory-startup --python-exit-code 2 --python tests/data/scenes/blender_figure.py
#
# The figure: eleven bones (hips, spine, head, two legs and two arms of two bones each), a tube
# around each bone (rings of eight vertices, capped), every vertex weighted to the bones near
# it (up to six influences, so the exporter writes JOINTS_1/WEIGHTS_1 too), two shape keys on
# the torso and head, and 30 frames at 30 fps of walking: legs and arms swinging, the spine
# twisting, both shape keys animated, the armature object moving forward. The exporter samples
# the animation at every frame, so at a frame's time giq poses from the keys Blender evaluated.
#
# blender_figure.json: "fps", and for each checked frame Blender's evaluated (armature and
# shape keys applied) world positions of the mesh's vertices in glTF's frame (y up), in
# Blender's vertex order; the test pairs them with the glTF's vertices at frame 0.

import json
import math
import os
import sys

import bmesh
import bpy
from mathutils import Quaternion, Vector

HERE = os.path.dirname(os.path.abspath(__file__))
FPS, LAST = 30, 30
CHECKED = [0, 7, 15, 22, 30]

BONES = [  # name, head, tail, parent, tube radius
    ("hips", (0, 0, 1.0), (0, 0, 1.15), None, 0.16),
    ("spine", (0, 0, 1.15), (0, 0, 1.45), "hips", 0.15),
    ("head", (0, 0, 1.5), (0, 0, 1.76), "spine", 0.11),
    ("thigh.L", (0.1, 0, 0.95), (0.1, 0, 0.53), "hips", 0.065),
    ("shin.L", (0.1, 0, 0.51), (0.1, 0, 0.08), "thigh.L", 0.055),
    ("thigh.R", (-0.1, 0, 0.95), (-0.1, 0, 0.53), "hips", 0.065),
    ("shin.R", (-0.1, 0, 0.51), (-0.1, 0, 0.08), "thigh.R", 0.055),
    ("arm.L", (0.2, 0, 1.42), (0.48, 0, 1.42), "spine", 0.05),
    ("forearm.L", (0.5, 0, 1.42), (0.76, 0, 1.42), "arm.L", 0.045),
    ("arm.R", (-0.2, 0, 1.42), (-0.48, 0, 1.42), "spine", 0.05),
    ("forearm.R", (-0.5, 0, 1.42), (-0.76, 0, 1.42), "arm.R", 0.045),
]


def fail(message):
    print(f"blender_figure.py: {message}", file=sys.stderr)
    sys.exit(2)


def build_armature():
    data = bpy.data.armatures.new("rig")
    rig = bpy.data.objects.new("rig", data)
    bpy.context.scene.collection.objects.link(rig)
    bpy.context.view_layer.objects.active = rig
    bpy.ops.object.mode_set(mode="EDIT")
    for name, head, tail, parent, _ in BONES:
        b = data.edit_bones.new(name)
        b.head, b.tail = Vector(head), Vector(tail)
        if parent:
            b.parent = data.edit_bones[parent]
    bpy.ops.object.mode_set(mode="OBJECT")
    return rig


def segment_distance(p, a, b):
    ab = b - a
    s = max(0.0, min(1.0, (p - a).dot(ab) / ab.dot(ab)))
    return (p - (a + s * ab)).length


def build_mesh(rig):
    bm = bmesh.new()
    for _, head, tail, _, radius in BONES:
        a, b = Vector(head), Vector(tail)
        axis = (b - a).normalized()
        u = axis.orthogonal().normalized()
        v = axis.cross(u)
        rings = []
        for k in range(6):
            centre = a + (b - a) * (k / 5)
            rings.append([bm.verts.new(centre + radius * (math.cos(2 * math.pi * j / 8) * u + math.sin(2 * math.pi * j / 8) * v))
                          for j in range(8)])
        for k in range(5):
            for j in range(8):
                bm.faces.new((rings[k][j], rings[k][(j + 1) % 8], rings[k + 1][(j + 1) % 8], rings[k + 1][j]))
        for ring, centre, flip in ((rings[0], a, True), (rings[-1], b, False)):
            c = bm.verts.new(centre + (-1 if flip else 1) * 0.3 * radius * axis)
            for j in range(8):
                tri = (ring[j], ring[(j + 1) % 8], c)
                bm.faces.new(tuple(reversed(tri)) if flip else tri)
    bmesh.ops.recalc_face_normals(bm, faces=bm.faces)
    mesh = bpy.data.meshes.new("figure")
    bm.to_mesh(mesh)
    bm.free()
    for poly in mesh.polygons:
        poly.use_smooth = True
    body = bpy.data.objects.new("figure", mesh)
    bpy.context.scene.collection.objects.link(body)

    # Weights: a Gaussian of the distance to each bone's segment, the six largest kept.
    groups = {name: body.vertex_groups.new(name=name) for name, *_ in BONES}
    for vert in mesh.vertices:
        w = [(math.exp(-(segment_distance(vert.co, Vector(h), Vector(t)) / 0.12) ** 2), name) for name, h, t, _, _ in BONES]
        w = sorted(w, reverse=True)[:6]
        total = sum(x for x, _ in w)
        for x, name in w:
            if x / total > 1e-3:
                groups[name].add([vert.index], x / total, "REPLACE")
    body.parent = rig
    body.modifiers.new("rig", "ARMATURE").object = rig

    # Shape keys: the torso breathes out, the head nods forward.
    body.shape_key_add(name="Basis")
    breathe, nod = body.shape_key_add(name="breathe"), body.shape_key_add(name="nod")
    for i, vert in enumerate(mesh.vertices):
        co = vert.co
        if 1.0 <= co.z <= 1.45 and abs(co.x) < 0.17:
            radial = Vector((co.x, co.y, 0.0))
            if radial.length > 1e-6:
                breathe.data[i].co = co + 0.03 * radial.normalized()
        if co.z >= 1.48 and abs(co.x) < 0.12:
            nod.data[i].co = co + Vector((0.0, -0.05, 0.02))
    return body, breathe, nod


def animate(rig, breathe, nod):
    scene = bpy.context.scene
    scene.render.fps = FPS
    scene.frame_start, scene.frame_end = 0, LAST
    swing = {"thigh.L": 1, "thigh.R": -1, "arm.L": -1, "arm.R": 1}
    for f in range(0, LAST + 1, 5):
        phase = 2 * math.pi * f / LAST
        for name, sign in swing.items():
            pb = rig.pose.bones[name]
            axis = (1, 0, 0) if name.startswith("thigh") else (0, 0, 1)
            pb.rotation_quaternion = Quaternion(axis, sign * math.radians(30) * math.sin(phase))
            pb.keyframe_insert("rotation_quaternion", frame=f)
        for name in ("shin.L", "shin.R", "forearm.L", "forearm.R"):
            pb = rig.pose.bones[name]
            pb.rotation_quaternion = Quaternion((1, 0, 0), math.radians(35) * max(0.0, math.sin(phase + (0 if name.endswith("L") else math.pi))))
            pb.keyframe_insert("rotation_quaternion", frame=f)
        spine = rig.pose.bones["spine"]
        spine.rotation_quaternion = Quaternion((0, 1, 0), math.radians(10) * math.sin(phase))
        spine.keyframe_insert("rotation_quaternion", frame=f)
        rig.location = (0.0, -0.6 * f / LAST, 0.02 * math.sin(2 * phase))
        rig.keyframe_insert("location", frame=f)
        breathe.value = 0.5 - 0.5 * math.cos(phase)
        breathe.keyframe_insert("value", frame=f)
        nod.value = f / LAST
        nod.keyframe_insert("value", frame=f)


def main():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    rig = build_armature()
    body, breathe, nod = build_mesh(rig)
    animate(rig, breathe, nod)
    glb = os.path.join(HERE, "blender_figure.glb")
    bpy.ops.export_scene.gltf(filepath=glb, export_format="GLB", export_yup=True, export_apply=False, export_animations=True,
                              export_force_sampling=True, export_nla_strips=False, export_def_bones=False, export_skins=True,
                              export_all_influences=True, export_morph=True, export_morph_normal=True, export_lights=False,
                              export_cameras=False)
    checked = {}
    scene = bpy.context.scene
    for f in CHECKED:
        scene.frame_set(f)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        evaluated = body.evaluated_get(depsgraph)
        mesh = evaluated.to_mesh()
        world = evaluated.matrix_world
        # Blender z up -> glTF y up: (x, y, z) -> (x, z, -y), as the exporter converts.
        checked[str(f)] = [[round(c, 7) for c in (p.x, p.z, -p.y)] for p in (world @ v.co for v in mesh.vertices)]
        evaluated.to_mesh_clear()
    with open(os.path.join(HERE, "blender_figure.json"), "w") as out:
        json.dump({"fps": FPS, "frames": checked}, out, separators=(",", ":"))
        out.write("\n")


main()
