# Renders a glTF scene with Blender's Cycles (CPU) at several sample counts, for the
# Cycles comparison of giq-bench-cycles. Runs inside Blender:
#
#   blender -b --factory-startup --python-exit-code 2 --python render_cycles.py -- \
#       --gltf scenes/cornell.gltf --out DIR --size 512 --threads 2 --seed 1 --spp 16,32,64 \
#       --camera=px,py,pz,fx,fy,fz,ux,uy,uz,yfov
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
#  - materials are rebuilt from the glTF's own JSON (rebuild_material): glTF's metallic-
#    roughness BRDF with KHR_materials_specular as a Lambert Diffuse BSDF plus GGX lobes of
#    Principled BSDFs with their diffuse part off, base colour, metallic-roughness, normal and
#    emissive textures read from the glTF's own image bytes, plus an Emission of emissiveFactor x
#    KHR_materials_emissive_strength (Cycles' mesh emission of strength s and colour c has
#    radiance s c, giq's units); for a one-sided material the back face is black (no BSDF,
#    no emission), as in giq; what the rebuild cannot reproduce (vertex colours, a second UV
#    set, texture transforms, alpha modes other than OPAQUE, other extensions) is refused;
#  - directional lights rebuilt as Sun lamps of angle 0 and strength = giq's illuminance
#    (the importer's photometric conversion is not giq's); point and spot lights refused;
#  - world black (giq's environment is refused); giq's --max-bounces counts scattering events (1 = direct light) while
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
import base64
import json
import math
import os
import sys
import time
import urllib.parse

import numpy

# Debian's Blender 3.4 glTF importer still uses numpy.bool, removed in numpy 1.24.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

import bpy  # noqa: E402
from mathutils import Matrix, Quaternion, Vector  # noqa: E402


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


def read_gltf(gltf_path):
    with open(gltf_path) as f:
        return json.load(f)


def buffer_bytes(doc, gltf_path, index):
    uri = doc["buffers"][index].get("uri")
    if uri is None:
        fail(f"{gltf_path}: buffers[{index}] has no uri (a .glb): the Cycles comparison reads .gltf files")
    if uri.startswith("data:"):
        return base64.b64decode(uri.split(",", 1)[1])
    with open(os.path.join(os.path.dirname(gltf_path), urllib.parse.unquote(uri)), "rb") as f:
        return f.read()


def load_images(doc, gltf_path, folder):
    """Every glTF image as a Blender image, by index, read from the glTF's own bytes (the
    importer's image names are not a stable key)."""
    images = []
    for i, im in enumerate(doc.get("images", [])):
        if "bufferView" in im:
            view = doc["bufferViews"][im["bufferView"]]
            data = buffer_bytes(doc, gltf_path, view["buffer"])
            start = view.get("byteOffset", 0)
            data = data[start:start + view["byteLength"]]
        elif im.get("uri", "").startswith("data:"):
            data = base64.b64decode(im["uri"].split(",", 1)[1])
        else:
            with open(os.path.join(os.path.dirname(gltf_path), urllib.parse.unquote(im["uri"])), "rb") as f:
                data = f.read()
        ext = ".jpg" if im.get("mimeType") == "image/jpeg" or im.get("uri", "").lower().endswith((".jpg", ".jpeg")) else ".png"
        path = os.path.join(folder, f"image{i}{ext}")
        with open(path, "wb") as f:
            f.write(data)
        img = bpy.data.images.load(path)
        img.pack()
        images.append(img)
    return images


def materials(doc, gltf_path):
    """giq's material parameters from the glTF's own JSON, by material name. What giq models
    and this rebuild cannot reproduce is refused, so that a comparison never runs on two
    different scenes unknowingly."""
    if "environment" in doc.get("extras", {}).get("giq", {}):
        fail(f"{gltf_path}: extras.giq.environment: the Cycles comparison does not rebuild giq's environment")
    for k, m in enumerate(doc.get("meshes", [])):
        for prim in m.get("primitives", []):
            if "COLOR_0" in prim.get("attributes", {}) or "TEXCOORD_1" in prim.get("attributes", {}):
                fail(f"{gltf_path}: meshes[{k}]: COLOR_0 or TEXCOORD_1: the Cycles comparison "
                     f"supports one UV set and no vertex colours")
    samplers = doc.get("samplers", [])

    def texture(info, field, name):
        if info is None:
            return None
        if info.get("texCoord", 0) != 0 or info.get("extensions"):
            fail(f"{gltf_path}: material '{name}': {field}: texCoord 0 without extensions expected")
        tex = doc["textures"][info["index"]]
        sampler = samplers[tex["sampler"]] if "sampler" in tex else {}
        if sampler.get("wrapS", 10497) != 10497 or sampler.get("wrapT", 10497) != 10497:
            fail(f"{gltf_path}: material '{name}': {field}: REPEAT wrapping expected")
        return {"image": tex["source"], "nearest": sampler.get("magFilter") == 9728}

    result = {}
    for i, m in enumerate(doc.get("materials", [])):
        name = m.get("name", f"material_{i}")
        pbr = m.get("pbrMetallicRoughness", {})
        ext = m.get("extensions", {})
        unsupported = set(ext) - {"KHR_materials_specular", "KHR_materials_emissive_strength"}
        if unsupported or m.get("alphaMode", "OPAQUE") != "OPAQUE":
            fail(f"{gltf_path}: material '{name}': {sorted(unsupported) or m.get('alphaMode')}: "
                 f"the Cycles comparison supports opaque metallic-roughness materials with "
                 f"KHR_materials_specular and KHR_materials_emissive_strength")
        spec = ext.get("KHR_materials_specular", {})
        if "specularTexture" in spec or "specularColorTexture" in spec:
            fail(f"{gltf_path}: material '{name}': KHR_materials_specular textures are not rebuilt")
        normal = m.get("normalTexture")
        if normal is not None and normal.get("scale", 1.0) != 1.0:
            fail(f"{gltf_path}: material '{name}': normalTexture.scale {normal['scale']}: "
                 f"Blender's Normal Map strength is not glTF's scale; 1 expected")
        strength = ext.get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
        specular = spec.get("specularFactor", 1.0)
        metallic = pbr.get("metallicFactor", 1.0)
        mr = texture(pbr.get("metallicRoughnessTexture"), "metallicRoughnessTexture", name)
        result[name] = {
            "base": pbr.get("baseColorFactor", [1.0, 1.0, 1.0, 1.0])[:3],
            "base_texture": texture(pbr.get("baseColorTexture"), "baseColorTexture", name),
            "metallic": metallic,
            "roughness": pbr.get("roughnessFactor", 1.0),
            "mr_texture": mr,
            "normal_texture": texture(normal, "normalTexture", name),
            "specular": specular,
            "specular_color": spec.get("specularColorFactor", [1.0, 1.0, 1.0]),
            # giq's Material::has_specular_lobe: no GGX lobe at all when it cannot reflect.
            "specular_lobe": not (metallic == 0.0 and mr is None and specular == 0.0),
            "emission": [strength * e for e in m.get("emissiveFactor", [0.0, 0.0, 0.0])],
            "emissive_texture": texture(m.get("emissiveTexture"), "emissiveTexture", name),
            "double_sided": bool(m.get("doubleSided", False)),
        }
    return result


class Graph:
    """A material's node tree, built from small arithmetic helpers."""

    def __init__(self, mat):
        mat.use_nodes = True
        self.nt = mat.node_tree
        self.nt.nodes.clear()

    def node(self, kind, **inputs):
        n = self.nt.nodes.new(kind)
        for key, value in inputs.items():
            self.set(n.inputs[key], value)
        return n

    def set(self, socket, value):
        if hasattr(value, "is_output") and value.is_output:
            self.nt.links.new(value, socket)
        elif isinstance(value, (list, tuple)):
            socket.default_value = (*value[:3], 1.0) if len(socket.default_value) == 4 else value
        else:
            socket.default_value = value

    def math(self, op, a, b=0.0):
        n = self.nt.nodes.new("ShaderNodeMath")
        n.operation = op
        self.set(n.inputs[0], a)
        self.set(n.inputs[1], b)
        return n.outputs[0]

    def rgb(self, op, a, b, fac=1.0):
        n = self.nt.nodes.new("ShaderNodeMixRGB")
        n.blend_type = op
        self.set(n.inputs["Fac"], fac)
        self.set(n.inputs["Color1"], a)
        self.set(n.inputs["Color2"], b)
        return n.outputs["Color"]

    def image(self, tex, images, colour):
        n = self.nt.nodes.new("ShaderNodeTexImage")
        n.image = images[tex["image"]]
        n.image.colorspace_settings.name = "sRGB" if colour else "Non-Color"
        n.interpolation = "Closest" if tex["nearest"] else "Linear"
        n.extension = "REPEAT"
        uv = self.nt.nodes.new("ShaderNodeUVMap")  # the first UV layer, TEXCOORD_0
        self.nt.links.new(uv.outputs["UV"], n.inputs["Vector"])
        return n.outputs["Color"]


def rebuild_material(mat, spec, images):
    """glTF's metallic-roughness BRDF with KHR_materials_specular as giq evaluates it
    (reference/include/giq/reference/bsdf.h):

      f = (1 - metallic) [(1 - F_d) base / pi + F_d D V] + metallic F_m D V

    A node graph cannot see the light direction, so the Fresnel terms, Schlick's at v.h in
    giq, are where the rebuild has to choose. The GGX lobes come from Cycles' Principled BSDF
    with the diffuse part switched off (base colour black for the dielectric lobe, metallic 1
    for the metal lobe): its Fresnel is per microfacet, at v.h, as giq's, from the dielectric
    Fresnel equations for IOR 1.5 (F0 = 0.04) rescaled to run from F0 to 1 (Cycles 3.4's
    interpolate_fresnel_color), not Schlick's fifth power. The Lambert lobe is a Diffuse BSDF
    of roughness 0 weighted by 1 - F_d at normal incidence: for most of a cosine-weighted
    hemisphere of light directions v.h is far from 0 whatever the view, so giq's 1 - F_d(v.h)
    stays near 1 - F_d(1). (A Glossy BSDF weighted by Schlick at n.v, Layer Weight's Facing, measured a
    sunlit floor seen from eye height 7 % too bright, and the same weight on the diffuse lobe
    a third too dark.) Principled's F90 is 1: a specularFactor strictly between 0 and 1 or a
    coloured specularColorFactor is refused. Cycles 3.4's GGX uses the separable Smith
    masking-shadowing term, giq the height-correlated one (Heitz 2014). These differences
    vanish for a Lambertian material; the benchmark measures what they leave as a squared
    bias. Tangent frames for normal maps are MikkTSpace's in Blender, the mesh's tangents or
    dp/du in giq: the same on planar, consistently mapped faces."""
    g = Graph(mat)
    base = spec["base"]
    if spec["base_texture"] is not None:
        base = g.rgb("MULTIPLY", g.image(spec["base_texture"], images, True), spec["base"])
    normal = None
    if spec["normal_texture"] is not None:
        nm = g.node("ShaderNodeNormalMap", Color=g.image(spec["normal_texture"], images, False))
        nm.space = "TANGENT"
        normal = nm.outputs["Normal"]
    metallic, roughness = spec["metallic"], spec["roughness"]
    if spec["mr_texture"] is not None:
        sep = g.node("ShaderNodeSeparateColor", Color=g.image(spec["mr_texture"], images, False))
        roughness = g.math("MULTIPLY", sep.outputs[1], roughness)  # G: roughness
        metallic = g.math("MULTIPLY", sep.outputs[2], metallic)  # B: metalness
    diffuse = g.node("ShaderNodeBsdfDiffuse", Roughness=0.0)  # Lambert, not Oren-Nayar
    if normal is not None:
        g.set(diffuse.inputs["Normal"], normal)
    front = diffuse.outputs["BSDF"]
    if not spec["specular_lobe"]:  # pure Lambert: metallic 0, no GGX lobe
        g.set(diffuse.inputs["Color"], base)
    else:
        if spec["specular"] not in (0.0, 1.0) or spec["specular_color"] != [1.0, 1.0, 1.0]:
            fail(f"material '{mat.name}': KHR_materials_specular {spec['specular']} "
                 f"{spec['specular_color']}: Principled's F90 is 1; factor 0 or 1 and a white "
                 f"colour expected")
        f0 = 0.04 * spec["specular"]

        def ggx_lobe(colour, metal):
            p = g.node("ShaderNodeBsdfPrincipled", Metallic=metal, Specular=f0 / 0.08,
                       Roughness=g.math("MAXIMUM", roughness, math.sqrt(1e-3)))  # giq's kMinAlpha
            p.distribution = "GGX"
            g.set(p.inputs["Base Color"], colour)
            for off in ("Subsurface", "Specular Tint", "Anisotropic", "Sheen", "Clearcoat", "Transmission"):
                g.set(p.inputs[off], 0.0)
            if normal is not None:
                g.set(p.inputs["Normal"], normal)
            return p.outputs["BSDF"]

        g.set(diffuse.inputs["Color"], g.rgb("MULTIPLY", base, [1.0 - f0] * 3))
        add = g.node("ShaderNodeAddShader")
        g.set(add.inputs[0], front)
        g.set(add.inputs[1], ggx_lobe([0.0, 0.0, 0.0], 0.0))  # black base: no diffuse part
        mix = g.node("ShaderNodeMixShader", Fac=metallic)
        g.set(mix.inputs[1], add.outputs["Shader"])
        g.set(mix.inputs[2], ggx_lobe(base, 1.0))
        front = mix.outputs["Shader"]
    emission = spec["emission"]
    if spec["emissive_texture"] is not None:
        emission = g.rgb("MULTIPLY", g.image(spec["emissive_texture"], images, True), emission)
    if spec["emissive_texture"] is not None or any(e > 0.0 for e in emission):
        e = g.node("ShaderNodeEmission", Color=emission, Strength=1.0)
        add = g.node("ShaderNodeAddShader")
        g.set(add.inputs[0], front)
        g.set(add.inputs[1], e.outputs["Emission"])
        front = add.outputs["Shader"]
    out = g.node("ShaderNodeOutputMaterial")
    if spec["double_sided"]:
        g.set(out.inputs["Surface"], front)
        return
    # One-sided: the back face neither reflects nor emits (a closure-free black surface
    # ends the path, as giq's back face does).
    geometry = g.node("ShaderNodeNewGeometry")
    black = g.node("ShaderNodeEmission", Strength=0.0)
    mix = g.node("ShaderNodeMixShader", Fac=geometry.outputs["Backfacing"])
    g.set(mix.inputs[1], front)
    g.set(mix.inputs[2], black.outputs["Emission"])
    g.set(out.inputs["Surface"], mix.outputs["Shader"])


def node_matrix(node):
    if "matrix" in node:
        m = node["matrix"]
        return Matrix([[m[c * 4 + r] for c in range(4)] for r in range(4)])
    t = Matrix.Translation(node.get("translation", [0.0, 0.0, 0.0]))
    q = node.get("rotation", [0.0, 0.0, 0.0, 1.0])
    r = Quaternion((q[3], q[0], q[1], q[2])).to_matrix().to_4x4()
    s = node.get("scale", [1.0, 1.0, 1.0])
    return t @ r @ Matrix.Diagonal((*s, 1.0))


def add_lights(doc, gltf_path, scene):
    """KHR_lights_punctual lights of the default scene at rest, rebuilt from the JSON: the
    importer converts intensities with photometric factors giq does not apply. A directional
    light of intensity E (giq's illuminance, linear units) is a Sun lamp of strength E and
    angle 0; point and spot lights are refused (their Cycles units are not giq's)."""
    lights = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    if not lights:
        return
    nodes = doc.get("nodes", [])

    def visit(index, parent):
        node = nodes[index]
        world = parent @ node_matrix(node)
        light_index = node.get("extensions", {}).get("KHR_lights_punctual", {}).get("light")
        if light_index is not None:
            light = lights[light_index]
            if light["type"] != "directional":
                fail(f"{gltf_path}: light '{light.get('name', light_index)}': {light['type']}: "
                     f"the Cycles comparison rebuilds directional lights only")
            direction = (world.to_3x3() @ Vector((0.0, 0.0, -1.0))).normalized()  # glTF: -z
            data = bpy.data.lights.new(f"giq_sun_{light_index}", "SUN")
            data.energy = light.get("intensity", 1.0)
            data.color = light.get("color", [1.0, 1.0, 1.0])
            data.angle = 0.0
            obj = bpy.data.objects.new(data.name, data)
            # A Sun lamp shines along its local -z.
            obj.rotation_euler = gltf_to_blender(direction).to_track_quat("-Z", "Y").to_euler()
            scene.collection.objects.link(obj)
        for child in node.get("children", []):
            visit(child, world)

    for root in doc["scenes"][doc.get("scene", 0)]["nodes"]:
        visit(root, Matrix.Identity(4))


def setup_scene(a):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    result = bpy.ops.import_scene.gltf(filepath=os.path.abspath(a.gltf))
    if "FINISHED" not in result:
        fail(f"{a.gltf}: Blender's glTF importer failed")
    doc = read_gltf(a.gltf)
    specs = materials(doc, a.gltf)
    images = load_images(doc, a.gltf, a.out)
    for mat in bpy.data.materials:
        if mat.name not in specs:
            fail(f"{a.gltf}: imported material '{mat.name}' not found in the glTF")
        rebuild_material(mat, specs[mat.name], images)
    scene = bpy.context.scene
    for obj in [o for o in scene.objects if o.type == "LIGHT"]:
        bpy.data.objects.remove(obj)
    add_lights(doc, a.gltf, scene)

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
