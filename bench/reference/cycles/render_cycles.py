# Renders a Lambertian glTF scene with Blender's Cycles (CPU) at several sample counts, for the
# Cycles comparison of giq-bench-cycles. Runs inside Blender:
#
#   blender -b --factory-startup --python-exit-code 2 --python render_cycles.py -- \
#       --gltf scenes/cornell.gltf --out DIR --size 512 --threads 2 --seed 1 --spp 16,32,64 \
#       --camera px,py,pz,fx,fy,fz,ux,uy,uz,yfov
#
# The camera is given in the glTF's frame (y up; position, unit forward and up, vertical field
# of view in radians), exactly giq's scenes::Camera, so that both renderers look through the
# same pinhole whatever view of the scene is compared. For each sample count, one independent
# render is timed (bpy.ops.render.render only, after an untimed warm-up render; the glTF is
# imported once) and written as a float32 EXR; one line per render goes to stdout:
#
#   giq-cycles spp=N seconds=T file=PATH
#
# after a line "giq-cycles ready" once the warm-up render is done. With --spp stdin the
# sample counts come one per line on standard input, so that a driver can alternate renders
# of another renderer with Cycles' own, one at a time, on a shared machine.
#
# Settings are chosen to compute what giq's reference renderer computes (docs/reference.md):
#  - materials are rebuilt from the glTF's own JSON: Diffuse BSDF with roughness 0 (Lambert)
#    of the base colour, plus an Emission of emissiveFactor x KHR_materials_emissive_strength
#    (Cycles' mesh emission of strength s and colour c has radiance s c, giq's units); for a
#    one-sided material the back face is black (no BSDF, no emission), as in giq; a material
#    that is not pure Lambert (metallic, specular, textures, transmission) is refused;
#  - world black; giq's --max-bounces counts scattering events (1 = direct light) while
#    Cycles counts the bounces after the first hit (0 = direct light), so Cycles gets one
#    less, of every kind;
#  - clamping off, light threshold 0 (Cycles' default 0.01 drops weak light samples),
#    glossy blur 0, adaptive sampling off, denoising off, path guiding off;
#  - box pixel filter of width 1 pixel: giq averages over each pixel's square;
#  - view transform Standard, look None, exposure 0, gamma 1, film exposure 1; the EXR holds
#    the linear scene-referred values (Rec.709 primaries, giq's linear RGB) regardless;
#  - CPU device, a fixed number of threads.
# Cycles' own sampler (progressive multi-jitter) is kept: its stratification is part of
# what the comparison measures.

import argparse
import json
import math
import os
import sys
import time

import numpy

# Debian's Blender 3.4 glTF importer still uses numpy.bool, removed in numpy 1.24.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

import bpy  # noqa: E402
from mathutils import Matrix, Vector  # noqa: E402


def fail(message):
    print(f"render_cycles.py: {message}", file=sys.stderr)
    sys.exit(2)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="render_cycles.py")
    p.add_argument("--gltf", required=True)
    p.add_argument("--out", required=True, help="folder of the EXR files")
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--threads", type=int, default=0, help="0 = all cores")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--spp", required=True,
                   help="comma-separated sample counts, or 'stdin': one count per line of standard input")
    p.add_argument("--max-bounces", type=int, default=64, help="giq's convention, >= 1")
    p.add_argument("--camera", required=True, help="px,py,pz,fx,fy,fz,ux,uy,uz,yfov (glTF frame)")
    p.add_argument("--tag", default="cycles", help="file name prefix")
    a = p.parse_args(argv)
    try:
        a.spp = None if a.spp == "stdin" else [int(s) for s in a.spp.split(",")]
        a.camera = [float(v) for v in a.camera.split(",")]
    except ValueError:
        fail(f"--spp and --camera take comma-separated numbers, got '{a.spp}' and '{a.camera}'")
    if len(a.camera) != 10 or any(s < 1 for s in a.spp or []) or a.size < 1 or a.max_bounces < 1:
        fail("--camera needs 10 numbers, --spp counts >= 1, --size >= 1, --max-bounces >= 1")
    return a


def gltf_to_blender(v):
    # The importer's axis conversion: glTF y up, -z forward -> Blender z up (x, -z, y).
    return Vector((v[0], -v[2], v[1]))


def lambert_materials(gltf_path):
    with open(gltf_path) as f:
        doc = json.load(f)
    if doc.get("textures"):
        fail(f"{gltf_path}: textures: the Cycles comparison supports untextured Lambert scenes only")
    # Light comes from emissive meshes only: the importer converts punctual lights with its own
    # photometric units, and giq's constant environment (extras.giq.environment) is not imported.
    if "KHR_lights_punctual" in doc.get("extensionsUsed", []) or "environment" in doc.get("extras", {}).get("giq", {}):
        fail(f"{gltf_path}: KHR_lights_punctual or extras.giq.environment: the Cycles comparison "
             f"supports scenes lit by emissive meshes only")
    result = {}
    for i, m in enumerate(doc.get("materials", [])):
        name = m.get("name", f"material_{i}")
        pbr = m.get("pbrMetallicRoughness", {})
        ext = m.get("extensions", {})
        specular = ext.get("KHR_materials_specular", {}).get("specularFactor", 1.0)
        unsupported = set(ext) - {"KHR_materials_specular", "KHR_materials_emissive_strength"}
        if pbr.get("metallicFactor", 1.0) != 0.0 or specular != 0.0 or unsupported:
            fail(f"{gltf_path}: material '{name}': expected pure Lambert (metallicFactor 0, "
                 f"KHR_materials_specular specularFactor 0, no other extension)")
        strength = ext.get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
        result[name] = {
            "base": pbr.get("baseColorFactor", [1.0, 1.0, 1.0, 1.0])[:3],
            "emission": [strength * e for e in m.get("emissiveFactor", [0.0, 0.0, 0.0])],
            "double_sided": bool(m.get("doubleSided", False)),
        }
    return result


def rebuild_material(mat, spec):
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*spec["base"], 1.0)
    diffuse.inputs["Roughness"].default_value = 0.0  # Lambert, not Oren-Nayar
    front = diffuse.outputs["BSDF"]
    if any(e > 0.0 for e in spec["emission"]):
        emission = nt.nodes.new("ShaderNodeEmission")
        emission.inputs["Color"].default_value = (*spec["emission"], 1.0)
        emission.inputs["Strength"].default_value = 1.0
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(front, add.inputs[0])
        nt.links.new(emission.outputs["Emission"], add.inputs[1])
        front = add.outputs["Shader"]
    if spec["double_sided"]:
        nt.links.new(front, out.inputs["Surface"])
        return
    # One-sided: the back face neither reflects nor emits (a closure-free black surface
    # ends the path, as giq's back face does).
    geometry = nt.nodes.new("ShaderNodeNewGeometry")
    black = nt.nodes.new("ShaderNodeEmission")
    black.inputs["Strength"].default_value = 0.0
    mix = nt.nodes.new("ShaderNodeMixShader")
    nt.links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
    nt.links.new(front, mix.inputs[1])
    nt.links.new(black.outputs["Emission"], mix.inputs[2])
    nt.links.new(mix.outputs["Shader"], out.inputs["Surface"])


def setup_scene(a):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    result = bpy.ops.import_scene.gltf(filepath=os.path.abspath(a.gltf))
    if "FINISHED" not in result:
        fail(f"{a.gltf}: Blender's glTF importer failed")
    specs = lambert_materials(a.gltf)
    for mat in bpy.data.materials:
        if mat.name not in specs:
            fail(f"{a.gltf}: imported material '{mat.name}' not found in the glTF")
        rebuild_material(mat, specs[mat.name])
    scene = bpy.context.scene

    # Camera from giq's (glTF-frame) pinhole: Blender cameras look along local -z, y up.
    for obj in [o for o in scene.objects if o.type == "CAMERA"]:
        bpy.data.objects.remove(obj)
    p, f, u, yfov = a.camera[0:3], a.camera[3:6], a.camera[6:9], a.camera[9]
    forward, up = gltf_to_blender(f).normalized(), gltf_to_blender(u).normalized()
    right = forward.cross(up).normalized()
    up = right.cross(forward)
    cam_data = bpy.data.cameras.new("giq")
    cam_data.sensor_fit = "VERTICAL"
    cam_data.sensor_height = 24.0
    cam_data.lens = 0.5 * cam_data.sensor_height / math.tan(0.5 * yfov)
    cam_data.clip_start = 1e-4
    cam_data.clip_end = 1e6
    cam = bpy.data.objects.new("giq", cam_data)
    scene.collection.objects.link(cam)
    rot = Matrix((right, up, -forward)).transposed()
    cam.matrix_world = Matrix.Translation(gltf_to_blender(p)) @ rot.to_4x4()
    scene.camera = cam

    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    scene.world = world

    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x = r.resolution_y = a.size
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.film_transparent = False
    r.use_persistent_data = False
    r.threads_mode = "FIXED" if a.threads > 0 else "AUTO"
    if a.threads > 0:
        r.threads = a.threads
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    r.image_settings.exr_codec = "ZIP"
    r.image_settings.color_mode = "RGB"

    v = scene.view_settings
    v.view_transform = "Standard"
    v.look = "None"
    v.exposure = 0.0
    v.gamma = 1.0

    c = scene.cycles
    c.device = "CPU"
    c.use_adaptive_sampling = False
    c.use_denoising = False
    bounces = a.max_bounces - 1
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = bounces
    c.transparent_max_bounces = bounces
    c.volume_bounces = 0
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = c.caustics_refractive = True
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.film_exposure = 1.0
    c.seed = a.seed
    c.use_animated_seed = False
    c.use_layer_samples = "IGNORE"
    if hasattr(c, "use_guiding"):
        c.use_guiding = False
    return scene


def main():
    a = parse_args()
    os.makedirs(a.out, exist_ok=True)
    scene = setup_scene(a)
    # Untimed warm-up (kernel set-up). Every timed render synchronises the scene and builds
    # its BVH again (milliseconds for a small scene): Blender 3.4 ignores a changed sample
    # count when use_persistent_data keeps the previous render's session.
    scene.cycles.samples = 1
    bpy.ops.render.render()
    # With --spp stdin, the caller interleaves its own renders between Cycles' renders: each
    # line read is rendered, answered, and the next is awaited.
    print("giq-cycles ready", flush=True)
    for spp in a.spp or (int(line) for line in sys.stdin if line.strip()):
        if spp < 1:
            fail(f"sample count {spp} read from stdin, expected >= 1")
        scene.cycles.samples = spp
        t0 = time.perf_counter()
        bpy.ops.render.render()
        seconds = time.perf_counter() - t0
        path = os.path.abspath(os.path.join(a.out, f"{a.tag}_seed{a.seed}_spp{spp}.exr"))
        bpy.data.images["Render Result"].save_render(path, scene=scene)
        print(f"giq-cycles spp={spp} seconds={seconds:.6f} file={path}", flush=True)


main()
