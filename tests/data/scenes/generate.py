#!/usr/bin/env python3
"""Writes the glTF test scenes of tests/scenes and tests/cli (valid ones here, hostile ones
under hostile/ with hostile/expected.tsv naming the glTF path each must be rejected at).

Run from anywhere: python3 tests/data/scenes/generate.py. The output is deterministic, so
re-running it gives the same bytes."""

import base64
import json
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
HOSTILE = os.path.join(HERE, "hostile")

FLOAT, USHORT, UINT, UBYTE, BYTE, SHORT = 5126, 5123, 5125, 5121, 5120, 5122


class Gltf:
    """A tiny glTF builder: one binary buffer (data URI unless written to a file)."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0", "generator": "giq tests/data/scenes/generate.py"}}
        self.bin = bytearray()

    def add(self, key, obj):
        self.doc.setdefault(key, []).append(obj)
        return len(self.doc[key]) - 1

    def view(self, data):
        while len(self.bin) % 4:
            self.bin.append(0)
        offset = len(self.bin)
        self.bin += data
        return self.add("bufferViews", {"buffer": 0, "byteOffset": offset, "byteLength": len(data)})

    def accessor(self, values, type_, ctype=FLOAT, minmax=False, **extra):
        n = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}[type_]
        fmt = {FLOAT: "f", USHORT: "H", UINT: "I", UBYTE: "B", BYTE: "b", SHORT: "h"}[ctype]
        flat = [x for v in values for x in (v if isinstance(v, (list, tuple)) else [v])]
        a = {"bufferView": self.view(struct.pack("<%d%s" % (len(flat), fmt), *flat)),
             "componentType": ctype, "count": len(flat) // n, "type": type_}
        if minmax:
            a["min"] = [min(flat[i::n]) for i in range(n)]
            a["max"] = [max(flat[i::n]) for i in range(n)]
        a.update(extra)
        return self.add("accessors", a)

    def mesh(self, name, positions, indices=None, normals=None, uvs=None, material=None, mode=None):
        attrs = {"POSITION": self.accessor(positions, "VEC3", minmax=True)}
        if normals:
            attrs["NORMAL"] = self.accessor(normals, "VEC3")
        if uvs:
            attrs["TEXCOORD_0"] = self.accessor(uvs, "VEC2")
        prim = {"attributes": attrs}
        if indices is not None:
            prim["indices"] = self.accessor(indices, "SCALAR", USHORT)
        if material is not None:
            prim["material"] = material
        if mode is not None:
            prim["mode"] = mode
        return self.add("meshes", {"name": name, "primitives": [prim]})

    def node(self, **kw):
        return self.add("nodes", kw)

    def finish(self, roots=None, external=None):
        d = dict(self.doc)
        if self.bin:
            while len(self.bin) % 4:
                self.bin.append(0)
            uri = external or "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode()
            d["buffers"] = [{"byteLength": len(self.bin), "uri": uri}]
        if roots is None:
            children = {c for n in d.get("nodes", []) for c in n.get("children", [])}
            roots = [i for i in range(len(d.get("nodes", []))) if i not in children]
        d["scenes"] = [{"nodes": roots}]
        d["scene"] = 0
        return d


def write(path, doc):
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def png_rgba(width, height, rows):
    """A minimal 8-bit RGBA PNG (ISO/IEC 15948: signature, IHDR, one IDAT, IEND)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\0" + bytes(c for px in row for c in px) for row in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


QUAD_P = [(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1)]
QUAD_I = [0, 2, 1, 0, 3, 2]  # counter-clockwise seen from +Y
QUAD_N = [(0, 1, 0)] * 4
TRI_P = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]  # counter-clockwise seen from +Z
S45 = math.sqrt(0.5)


def transforms():
    g = Gltf()
    quad = g.mesh("quad", QUAD_P, QUAD_I, QUAD_N)
    tri = g.mesh("tri", TRI_P)
    g.node(name="parent", mesh=quad, translation=[10, 0, 0], scale=[2, 2, 2], children=[1])
    g.node(name="child", mesh=tri, translation=[0, 1, 0], rotation=[0, 0, S45, S45])  # 90 deg about +Z
    g.node(name="mirror", mesh=tri, scale=[-1, 1, 1])
    g.node(mesh=tri, matrix=[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1])
    return g.finish()


def strip_fan():
    g = Gltf()
    prims = []
    strip = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)]
    prims.append({"attributes": {"POSITION": g.accessor(strip, "VEC3", minmax=True)}, "mode": 5})
    fan = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (-1, 1, 0)]
    prims.append({"attributes": {"POSITION": g.accessor(fan, "VEC3", minmax=True)}, "mode": 6})
    # Triangles 1 (repeated vertex) and 2 (collinear) have no area.
    tris = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (2, 0, 0)]
    prims.append({"attributes": {"POSITION": g.accessor(tris, "VEC3", minmax=True)},
                  "indices": g.accessor([0, 1, 2, 0, 0, 1, 0, 1, 3], "SCALAR", USHORT)})
    # Sparse positions over an all-zero base: vertices 1 and 2 replaced.
    sp = {"count": 2, "indices": {"bufferView": g.view(struct.pack("<2H", 1, 2)), "componentType": USHORT},
          "values": {"bufferView": g.view(struct.pack("<6f", 1, 0, 0, 0, 1, 0))}}
    acc = g.add("accessors", {"componentType": FLOAT, "count": 3, "type": "VEC3", "sparse": sp,
                              "min": [0, 0, 0], "max": [1, 1, 0]})
    prims.append({"attributes": {"POSITION": acc}})
    m = g.add("meshes", {"name": "modes", "primitives": prims})
    g.node(name="modes", mesh=m)
    return g.finish()


def textured():
    g = Gltf()
    # Texel (row, column): sRGB-encoded 8-bit values with known linear values.
    png = png_rgba(2, 2, [[(255, 128, 0, 255), (188, 64, 32, 128)], [(0, 0, 0, 255), (255, 255, 255, 255)]])
    g.add("images", {"name": "checker", "uri": "data:image/png;base64," + base64.b64encode(png).decode()})
    g.add("samplers", {"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33648})
    g.add("textures", {"source": 0, "sampler": 0})
    g.add("materials", {
        "name": "textured",
        "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 0},
                                 "metallicFactor": 0.0},
        "emissiveTexture": {"index": 0}, "emissiveFactor": [1, 1, 1],
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2.0}},
    })
    g.doc["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    # A unit quad in the XY plane with UV (0,0) at its top-left, covering the whole texture.
    quad = g.mesh("screen", [(0, 1, 0), (1, 1, 0), (1, 0, 0), (0, 0, 0)], [0, 3, 2, 0, 2, 1],
                  [(0, 0, 1)] * 4, [(0, 0), (1, 0), (1, 1), (0, 1)], material=0)
    g.node(name="screen", mesh=quad)
    return g.finish()


def uv_sets():
    """Texture coordinates as real assets use them: a second UV set, KHR_texture_transform (the
    extension's own example), and a transform's texCoord override."""
    g = Gltf()
    png = png_rgba(1, 1, [[(255, 255, 255, 255)]])
    g.add("images", {"uri": "data:image/png;base64," + base64.b64encode(png).decode()})
    g.add("textures", {"source": 0})
    example = {"offset": [0, 1], "rotation": 1.57079632679, "scale": [0.5, 0.5]}
    g.add("materials", {"name": "second_set_transformed",
                        "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1,
                                                                      "extensions": {"KHR_texture_transform": example}}},
                        "emissiveTexture": {"index": 0, "texCoord": 1, "extensions": {"KHR_texture_transform": example}}})
    g.add("materials", {"name": "override", "pbrMetallicRoughness": {"baseColorTexture": {
        "index": 0, "extensions": {"KHR_texture_transform": {"texCoord": 1, "offset": [0.25, 0]}}}}})
    g.doc["extensionsUsed"] = ["KHR_texture_transform"]
    uv0 = [(0, 0), (1, 0), (1, 1), (0, 1)]
    uv1 = [(0, 0), (1, 0), (1, 1), (0, 1)]
    for k, name in enumerate(["transformed", "override"]):
        attrs = {"POSITION": g.accessor([(x + 3 * k, y, z) for x, y, z in QUAD_P], "VEC3", minmax=True),
                 "TEXCOORD_0": g.accessor([(u + 7, v) for u, v in uv0], "VEC2"),
                 "TEXCOORD_1": g.accessor(uv1, "VEC2")}
        m = g.add("meshes", {"name": name, "primitives": [{"attributes": attrs, "indices": g.accessor(QUAD_I, "SCALAR", USHORT),
                                                           "material": k}]})
        g.node(name=name, mesh=m)
    return g.finish()


def two_uv_sets():
    """Textures on two texture-coordinate mappings in one material, as MultiUVTest and
    TextureTransformMultiTest have them: an sRGB checker base colour on TEXCOORD_0, and an
    emissive texture and a normal map (no TANGENT: the tangent frame comes from TEXCOORD_1's
    own dp/du) on TEXCOORD_1 with a KHR_texture_transform. The floor emits and is lit by a
    point light; white walls show both. The real-time tests compare `pt` with the reference."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_texture_transform"]

    def texture(png, sampler):
        return g.add("textures", {"source": g.add("images", {"uri": "data:image/png;base64," + base64.b64encode(png).decode()}),
                                  "sampler": sampler})

    linear = g.add("samplers", {"magFilter": 9729, "wrapS": 10497, "wrapT": 10497})
    nearest = g.add("samplers", {"magFilter": 9728, "wrapS": 10497, "wrapT": 10497})
    checker = png_rgba(4, 4, [[(220, 200, 60, 255) if (x + y) % 2 else (60, 120, 220, 255) for x in range(4)] for y in range(4)])
    glow = png_rgba(2, 2, [[(255, 60, 20, 255), (10, 10, 10, 255)], [(10, 10, 10, 255), (40, 255, 80, 255)]])
    bumps = []
    for x in range(8):
        tilt = 0.6 * math.sin(2 * math.pi * (x + 0.5) / 8)
        length = math.sqrt(tilt * tilt + 1.0)
        bumps.append(tuple(int(round(255 * (0.5 * c / length + 0.5))) for c in (tilt, 0.0, 1.0)) + (255,))
    normal = png_rgba(8, 1, [bumps])
    transform = {"KHR_texture_transform": {"offset": [0.25, 0], "rotation": 0.5, "scale": [2, 1.5]}}
    floor_m = g.add("materials", {
        "name": "two_sets",
        "pbrMetallicRoughness": {"baseColorTexture": {"index": texture(checker, linear)}, "metallicFactor": 0.0, "roughnessFactor": 0.7},
        "emissiveTexture": {"index": texture(glow, nearest), "texCoord": 1, "extensions": transform},
        "emissiveFactor": [1, 1, 1],
        "normalTexture": {"index": texture(normal, linear), "texCoord": 1, "extensions": transform},
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 1.5}}})
    wall_m = g.add("materials", {"name": "white", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0.0},
                                 "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}})
    g.doc["extensionsUsed"].append("KHR_materials_specular")

    def quad(name, p, material, uv0=None, uv1=None):
        a, b, c = p[0], p[1], p[2]
        e1 = [b[i] - a[i] for i in range(3)]
        e2 = [c[i] - a[i] for i in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        length = math.sqrt(sum(x * x for x in n))
        attrs = {"POSITION": g.accessor(p, "VEC3", minmax=True), "NORMAL": g.accessor([[x / length for x in n]] * 4, "VEC3")}
        if uv0:
            attrs["TEXCOORD_0"] = g.accessor(uv0, "VEC2")
        if uv1:
            attrs["TEXCOORD_1"] = g.accessor(uv1, "VEC2")
        m = g.add("meshes", {"name": name, "primitives": [
            {"attributes": attrs, "indices": g.accessor([0, 1, 2, 0, 2, 3], "SCALAR", USHORT), "material": material}]})
        g.node(name=name, mesh=m)

    # TEXCOORD_0 tiles the checker twice; TEXCOORD_1 runs the other way round the quad.
    quad("floor", [(-1.5, 0, 1.5), (1.5, 0, 1.5), (1.5, 0, -1.5), (-1.5, 0, -1.5)], floor_m,
         uv0=[(0, 2), (2, 2), (2, 0), (0, 0)], uv1=[(1, 0), (1, 1), (0, 1), (0, 0)])
    quad("back", [(-1.5, 0, -1.5), (1.5, 0, -1.5), (1.5, 2.5, -1.5), (-1.5, 2.5, -1.5)], wall_m)
    quad("left", [(-1.5, 0, 1.5), (-1.5, 0, -1.5), (-1.5, 2.5, -1.5), (-1.5, 2.5, 1.5)], wall_m)
    quad("right", [(1.5, 0, -1.5), (1.5, 0, 1.5), (1.5, 2.5, 1.5), (1.5, 2.5, -1.5)], wall_m)
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"name": "bulb", "type": "point", "intensity": 4.0}]}}
    g.node(name="bulb", translation=[0.5, 2.0, 0.5], extensions={"KHR_lights_punctual": {"light": 0}})
    d = g.finish()
    d["extras"] = {"giq": {"views": [{"name": "front", "eye": [0, 2.0, 3.4], "target": [0, 0.4, 0], "yfov_deg": 60}]}}
    return d


def extensions():
    """Extensions real assets use that giq maps onto its materials at load (unlit, ior),
    primitives it drops with a warning (points, lines) and optional extensions it ignores."""
    g = Gltf()
    g.add("materials", {"name": "unlit", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 0.5], "metallicFactor": 0.5},
                        "extensions": {"KHR_materials_unlit": {}}})
    g.add("materials", {"name": "ior2", "pbrMetallicRoughness": {"metallicFactor": 0.0},
                        "extensions": {"KHR_materials_ior": {"ior": 2.0}, "KHR_materials_clearcoat": {"clearcoatFactor": 1.0}}})
    # Specular-glossiness: texel 0 specular (64, 128, 255) glossiness 64, texel 1 glossiness 255.
    sg = png_rgba(2, 1, [[(64, 128, 255, 64), (0, 0, 0, 255)]])
    g.add("images", {"uri": "data:image/png;base64," + base64.b64encode(sg).decode()})
    g.add("textures", {"source": 0})
    for gloss in (1.0, 0.75):
        g.add("materials", {"name": "specgloss%g" % gloss, "extensions": {"KHR_materials_pbrSpecularGlossiness": {
            "diffuseFactor": [0.5, 0.25, 0.125, 1.0], "specularFactor": [0.02, 0.04, 0.08], "glossinessFactor": gloss,
            "specularGlossinessTexture": {"index": 0}}}})
    g.doc["extensionsUsed"] = ["KHR_materials_unlit", "KHR_materials_ior", "KHR_materials_clearcoat", "KHR_xmp_json_ld", "EXT_made_up",
                               "KHR_materials_pbrSpecularGlossiness"]
    tri = g.accessor(TRI_P, "VEC3", minmax=True)
    prims = [{"attributes": {"POSITION": tri}, "material": 0}, {"attributes": {"POSITION": tri}, "material": 1},
             {"attributes": {"POSITION": tri}, "mode": 0}, {"attributes": {"POSITION": tri}, "mode": 3}]
    m = g.add("meshes", {"name": "mixed", "primitives": prims})
    g.node(name="mixed", mesh=m)
    return g.finish()


def instancing():
    """EXT_mesh_gpu_instancing (three instances of a triangle under a translated node) and
    KHR_mesh_quantization (16-bit integer positions scaled by the node, 8-bit normalized normals,
    8-bit integer UVs)."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["EXT_mesh_gpu_instancing", "KHR_mesh_quantization"]
    g.doc["extensionsRequired"] = ["KHR_mesh_quantization"]
    pos = g.accessor([(0, 0, 0), (1000, 0, 0), (0, 1000, 0)], "VEC3", SHORT, minmax=True)
    nrm = g.accessor([(0, 0, 127, 0)] * 3, "VEC4", BYTE, normalized=True)  # VEC3 padded to 4 bytes
    g.doc["accessors"][nrm]["type"] = "VEC3"
    g.doc["bufferViews"][g.doc["accessors"][nrm]["bufferView"]]["byteStride"] = 4
    uv = g.accessor([(0, 0, 0, 0), (2, 0, 0, 0), (0, 2, 0, 0)], "VEC4", UBYTE)  # VEC2 padded to 4 bytes
    g.doc["accessors"][uv]["type"] = "VEC2"
    g.doc["bufferViews"][g.doc["accessors"][uv]["bufferView"]]["byteStride"] = 4
    m = g.add("meshes", {"name": "tri", "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv}}]})
    t = g.accessor([(0, 0, 0), (10, 0, 0), (0, 0, 10)], "VEC3")
    r = g.accessor([(0, 0, 0, 1), (0, 0, 0.70710678, 0.70710678), (0, 0, 0, 1)], "VEC4")
    sc = g.accessor([(1, 1, 1), (1, 1, 1), (2, 2, 2)], "VEC3")
    g.node(name="crowd", mesh=m, translation=[0, 5, 0], scale=[0.001, 0.001, 0.001],
           extensions={"EXT_mesh_gpu_instancing": {"attributes": {"TRANSLATION": t, "ROTATION": r, "SCALE": sc}}})
    return g.finish()


def animated():
    g = Gltf()
    tri = g.mesh("tri", TRI_P)
    g.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "bulb", "type": "point", "intensity": 5.0},
        {"name": "sun", "type": "directional", "intensity": 2.0}]}}
    g.add("cameras", {"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.05}})
    g.node(name="mover", mesh=tri, extensions={"KHR_lights_punctual": {"light": 0}})  # 0: LINEAR translation
    g.node(name="turner", extensions={"KHR_lights_punctual": {"light": 1}})  # 1: LINEAR rotation
    g.node(name="grower", mesh=tri)  # 2: STEP scale
    g.node(name="glider", camera=0)  # 3: CUBICSPLINE translation
    t3 = g.accessor([0.0, 1.0, 2.0], "SCALAR", minmax=True)
    t2 = g.accessor([0.0, 2.0], "SCALAR", minmax=True)
    t1 = g.accessor([0.0, 1.0], "SCALAR", minmax=True)
    samplers = [
        {"input": t3, "output": g.accessor([(0, 0, 0), (1, 0, 0), (1, 2, 0)], "VEC3"), "interpolation": "LINEAR"},
        {"input": t2, "output": g.accessor([(0, 0, 0, 1), (0, S45, 0, S45)], "VEC4"), "interpolation": "LINEAR"},
        {"input": t1, "output": g.accessor([(1, 1, 1), (2, 2, 2)], "VEC3"), "interpolation": "STEP"},
        # CUBICSPLINE: per key in-tangent, value, out-tangent.
        {"input": t2, "output": g.accessor([(0, 0, 0), (0, 0, 0), (3, 0, 0), (0, 0, 0), (1, 0, 0), (0, 0, 0)], "VEC3"),
         "interpolation": "CUBICSPLINE"},
    ]
    channels = [{"sampler": 0, "target": {"node": 0, "path": "translation"}},
                {"sampler": 1, "target": {"node": 1, "path": "rotation"}},
                {"sampler": 2, "target": {"node": 2, "path": "scale"}},
                {"sampler": 3, "target": {"node": 3, "path": "translation"}}]
    g.add("animations", {"name": "move", "samplers": samplers, "channels": channels})
    d = g.finish()
    d["extras"] = {"giq": {"sequence": {"frames": 61, "fps": 30, "animation": "move"}}}
    return d


def skinned():
    """A strip 0.5 wide and 2 high in the z = 0 plane, skinned to two joints: "hip" at the rig's
    origin and "knee" 1 above it. Rows at y <= 0.5 follow the hip, rows at y >= 1.5 the knee, the
    row at y = 1 both halves, split over JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1. The "bend"
    animation turns the knee 90 degrees about +x over 1 s. The rig sits at z = -2 (the strip hangs
    2 in front of its joints) and the inverse bind matrices undo that, so the strip is where its
    positions say at rest; the mesh node's own translation (5, 0, 0) must be ignored (glTF 2.0
    spec, 3.7.3.3)."""
    g = Gltf()
    rows = [0.0, 0.5, 1.0, 1.5, 2.0]
    positions = [(x, y, 0.0) for y in rows for x in (-0.25, 0.25)]
    normals = [(0.0, 0.0, 1.0)] * len(positions)
    indices = []
    for r in range(len(rows) - 1):
        a, b, c, d = 2 * r, 2 * r + 1, 2 * r + 3, 2 * r + 2
        indices += [a, b, c, a, c, d]
    joints0, weights0, joints1, weights1 = [], [], [], []
    for y in rows:
        for _ in (0, 1):
            if y < 1.0:
                joints0.append((0, 0, 0, 0)), weights0.append((1.0, 0.0, 0.0, 0.0))
                joints1.append((0, 0, 0, 0)), weights1.append((0.0, 0.0, 0.0, 0.0))
            elif y > 1.0:
                joints0.append((1, 0, 0, 0)), weights0.append((1.0, 0.0, 0.0, 0.0))
                joints1.append((0, 0, 0, 0)), weights1.append((0.0, 0.0, 0.0, 0.0))
            else:
                joints0.append((0, 1, 0, 0)), weights0.append((0.25, 0.25, 0.0, 0.0))
                joints1.append((1, 0, 0, 0)), weights1.append((0.25, 0.25, 0.0, 0.0))
    attrs = {"POSITION": g.accessor(positions, "VEC3", minmax=True), "NORMAL": g.accessor(normals, "VEC3"),
             "JOINTS_0": g.accessor(joints0, "VEC4", UBYTE), "WEIGHTS_0": g.accessor(weights0, "VEC4"),
             "JOINTS_1": g.accessor(joints1, "VEC4", USHORT), "WEIGHTS_1": g.accessor(weights1, "VEC4")}
    mesh = g.add("meshes", {"name": "strip", "primitives": [{"attributes": attrs, "indices": g.accessor(indices, "SCALAR", USHORT)}]})
    # Column-major inverse bind matrices: the inverses of translate(0, 0, -2) and translate(0, 1, -2).
    def translation(x, y, z):
        return (1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, y, z, 1)
    ibm = g.accessor([translation(0, 0, 2), translation(0, -1, 2)], "MAT4")
    g.node(name="body", mesh=mesh, skin=0, translation=[5.0, 0.0, 0.0])
    g.node(name="rig", translation=[0.0, 0.0, -2.0], children=[2])
    g.node(name="hip", children=[3])
    g.node(name="knee", translation=[0.0, 1.0, 0.0])
    g.add("skins", {"joints": [2, 3], "inverseBindMatrices": ibm, "skeleton": 1})
    t = g.accessor([0.0, 1.0], "SCALAR", minmax=True)
    q = g.accessor([(0, 0, 0, 1), (S45, 0, 0, S45)], "VEC4")
    g.add("animations", {"name": "bend", "samplers": [{"input": t, "output": q, "interpolation": "LINEAR"}],
                         "channels": [{"sampler": 0, "target": {"node": 3, "path": "rotation"}}]})
    d = g.finish(roots=[0, 1])
    d["extras"] = {"giq": {"sequence": {"frames": 31, "fps": 30, "animation": "bend"},
                           "views": [{"name": "front", "eye": [0, 1, 4], "target": [0, 1, 0], "yfov_deg": 60}]}}
    return d


def morphed():
    """A unit quad in the z = 0 plane with two morph targets: target 0 lifts the top edge by 0.5
    along +z (and tilts the normals), target 1 moves the right edge 0.5 along +x. Node "a"
    (translated by (1, 2, 3)) takes the mesh's weights (0.25, 0); node "b" its own (0, 1). The
    "breathe" animation moves a's weights LINEAR from (0, 0) to (1, 0.5) over 1 s, and b's
    CUBICSPLINE from (0, 1) to (1, 0) with flat tangents."""
    g = Gltf()
    positions = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)]
    target0 = {"POSITION": g.accessor([(0, 0, 0), (0, 0, 0), (0, 0, 0.5), (0, 0, 0.5)], "VEC3"),
               "NORMAL": g.accessor([(0, -0.4, 0)] * 4, "VEC3")}
    target1 = {"POSITION": g.accessor([(0, 0, 0), (0.5, 0, 0), (0.5, 0, 0), (0, 0, 0)], "VEC3")}
    prim = {"attributes": {"POSITION": g.accessor(positions, "VEC3", minmax=True), "NORMAL": g.accessor([(0.0, 0.0, 1.0)] * 4, "VEC3")},
            "indices": g.accessor([0, 1, 2, 0, 2, 3], "SCALAR", USHORT), "targets": [target0, target1]}
    mesh = g.add("meshes", {"name": "quad", "primitives": [prim], "weights": [0.25, 0.0]})
    g.node(name="a", mesh=mesh, translation=[1.0, 2.0, 3.0])
    g.node(name="b", mesh=mesh, weights=[0.0, 1.0])
    t = g.accessor([0.0, 1.0], "SCALAR", minmax=True)
    linear = g.accessor([0.0, 0.0, 1.0, 0.5], "SCALAR")
    # CUBICSPLINE: per key in-tangents, values, out-tangents, each one number per target.
    cubic = g.accessor([0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0], "SCALAR")
    g.add("animations", {"name": "breathe", "samplers": [{"input": t, "output": linear, "interpolation": "LINEAR"},
                                                          {"input": t, "output": cubic, "interpolation": "CUBICSPLINE"}],
                         "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}},
                                      {"sampler": 1, "target": {"node": 1, "path": "weights"}}]})
    d = g.finish()
    d["extras"] = {"giq": {"sequence": {"frames": 31, "fps": 30, "animation": "breathe"},
                           "views": [{"name": "front", "eye": [1, 2, 6], "target": [1, 2, 0], "yfov_deg": 60}]}}
    return d


def collapsing():
    """A unit quad whose one morph target moves corner 3 onto corner 0, so that at weight 1
    (t = 1 s of "collapse") the triangle (0, 2, 3) has no area: the same quad with normals
    (node "indexed") and without (node "flat", flat normals)."""
    g = Gltf()
    positions = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)]
    target = {"POSITION": g.accessor([(0, 0, 0), (0, 0, 0), (0, 0, 0), (0, -1, 0)], "VEC3")}
    indices = g.accessor([0, 1, 2, 0, 2, 3], "SCALAR", USHORT)
    pos = g.accessor(positions, "VEC3", minmax=True)
    with_normals = {"attributes": {"POSITION": pos, "NORMAL": g.accessor([(0.0, 0.0, 1.0)] * 4, "VEC3")}, "indices": indices, "targets": [target]}
    flat = {"attributes": {"POSITION": pos}, "indices": indices, "targets": [target]}
    g.node(name="indexed", mesh=g.add("meshes", {"primitives": [with_normals]}))
    g.node(name="flat", mesh=g.add("meshes", {"primitives": [flat]}))
    t = g.accessor([0.0, 1.0], "SCALAR", minmax=True)
    w = g.accessor([0.0, 1.0], "SCALAR")
    g.add("animations", {"name": "collapse", "samplers": [{"input": t, "output": w}],
                         "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}},
                                      {"sampler": 0, "target": {"node": 1, "path": "weights"}}]})
    return g.finish()


def area_shapes():
    """An emissive quad declaring itself a rectangle light (meshes[0].extras.giq.area_light),
    and a plain floor under it."""
    g = Gltf()
    lamp = g.add("materials", {"name": "lamp", "emissiveFactor": [1.0, 1.0, 1.0]})
    g.mesh("lamp", [(-0.5, 1.0, -0.2), (-0.5, 1.0, 0.2), (0.5, 1.0, 0.2), (0.5, 1.0, -0.2)], [0, 1, 2, 0, 2, 3], material=lamp)
    g.doc["meshes"][0]["extras"] = {"giq": {"area_light": "rectangle"}}
    g.mesh("floor", QUAD_P, QUAD_I, QUAD_N)
    g.node(name="lamp", mesh=0)
    g.node(name="floor", mesh=1)
    return g.finish()


def fountain():
    """A particle fountain: a 0.2 m square nozzle facing up 0.1 above a 4 m floor emits 200
    particles a second (extras.giq.emitters), 1.2 s each, at 3 m/s within 15 degrees of the
    normal, under gravity and a little drag; they glow orange, brightest a tenth into their life,
    in four stages. 31 frames at 30 fps, with nothing animated but the particles."""
    g = Gltf()
    g.mesh("floor", [(-2.0, 0.0, 2.0), (2.0, 0.0, 2.0), (2.0, 0.0, -2.0), (-2.0, 0.0, -2.0)], [0, 1, 2, 0, 2, 3], [(0.0, 1.0, 0.0)] * 4)
    g.mesh("nozzle", [(-0.1, 0.1, 0.1), (0.1, 0.1, 0.1), (0.1, 0.1, -0.1), (-0.1, 0.1, -0.1)], [0, 1, 2, 0, 2, 3], [(0.0, 1.0, 0.0)] * 4)
    g.node(name="floor", mesh=0)
    g.node(name="nozzle", mesh=1)
    d = g.finish()
    d["extras"] = {"giq": {
        "sequence": {"frames": 31, "fps": 30},
        "views": [{"name": "side", "eye": [0, 1, 4], "target": [0, 0.8, 0], "yfov_deg": 50}],
        "emitters": [{"name": "fountain", "node": "nozzle", "rate": 200, "lifetime": 1.2, "speed": 3.0, "spread_deg": 15,
                      "drag": 0.3, "size": 0.01, "color": [0.8, 0.8, 0.8], "emission": [8, 5, 2],
                      "strength": [[0, 0], [0.1, 1], [1, 0]], "stages": 4, "seed": 7}]}}
    return d


def lights_cameras():
    g = Gltf()
    quad = g.mesh("floor", QUAD_P, QUAD_I, QUAD_N)
    g.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    g.doc["extensionsRequired"] = ["KHR_lights_punctual"]
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "sun", "type": "directional", "color": [1.0, 0.9, 0.8], "intensity": 3.0},
        {"type": "point", "intensity": 10.0, "range": 5.0},
        {"name": "spot", "type": "spot", "intensity": 20.0, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}}]}}
    g.add("cameras", {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100.0}})
    g.add("cameras", {"name": "overview", "type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.1}})
    # A negative ymag is taken by its magnitude (with a warning); the node's scale scales it.
    g.add("cameras", {"name": "plan", "type": "orthographic", "orthographic": {"xmag": 3.0, "ymag": -1.5, "znear": 0.0, "zfar": 20.0}})
    g.node(name="room", children=[1, 2, 3, 4, 5, 6, 7], translation=[100, 0, 0])
    g.node(name="floor", mesh=quad)
    g.node(name="sun", rotation=[-S45, 0, 0, S45], extensions={"KHR_lights_punctual": {"light": 0}})  # -90 deg about X
    g.node(name="bulb", translation=[0, 2, 0], extensions={"KHR_lights_punctual": {"light": 1}})
    g.node(name="spot", translation=[0, 3, 0], rotation=[-S45, 0, 0, S45], extensions={"KHR_lights_punctual": {"light": 2}})
    g.node(name="cam", translation=[0, 1, 5], camera=0)
    g.node(translation=[0, 10, 0], rotation=[-S45, 0, 0, S45], camera=1)
    g.node(translation=[0, 0, 8], scale=[2, 2, 2], camera=2)
    d = g.finish()
    d["extras"] = {"giq": {
        "views": [{"name": "corner", "eye": [104, 1, 4], "target": [100, 1, 0], "yfov_deg": 60},
                  {"name": "top", "eye": [100, 5, 0], "target": [100, 0, 0], "up": [0, 0, -1]},
                  {"name": "side", "eye": [100, 1, 9], "target": [100, 1, 0], "ymag": 2.5}],
        "sequence": {"frames": 1, "fps": 24},
        "leak_regions": ["floor"],
        "environment": {"radiance": [0.1, 0.2, 0.3]}}}
    return d


def materials():
    g = Gltf()
    png = png_rgba(1, 1, [[(128, 128, 255, 255)]])
    g.add("images", {"uri": "data:image/png;base64," + base64.b64encode(png).decode()})
    g.add("textures", {"source": 0})
    g.doc["extensionsUsed"] = ["KHR_materials_specular", "KHR_materials_emissive_strength"]
    g.add("materials", {  # Lambert: dielectric with the specular layer switched off
        "name": "lambert", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 1.0], "metallicFactor": 0.0},
        "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}})
    g.add("materials", {  # glossy dielectric, alpha-masked, double-sided, normal-mapped
        "name": "masked", "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.3},
        "alphaMode": "MASK", "alphaCutoff": 0.25, "doubleSided": True,
        "normalTexture": {"index": 0, "scale": 0.5},
        "extensions": {"KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [1.0, 0.5, 0.25],
                                                  "specularColorTexture": {"index": 0}}}})
    g.add("materials", {  # emitter: factor x strength; BLEND, half transparent
        "name": "lamp", "emissiveFactor": [1.0, 0.5, 0.25], "alphaMode": "BLEND",
        "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 0.5]},
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8.0}}})
    uvs = [(0, 0), (1, 0), (1, 1), (0, 1)]
    tangents = [(1, 0, 0, 1)] * 4
    for k in range(3):
        attrs = {"POSITION": g.accessor(QUAD_P, "VEC3", minmax=True), "NORMAL": g.accessor(QUAD_N, "VEC3"),
                 "TEXCOORD_0": g.accessor(uvs, "VEC2"), "TANGENT": g.accessor(tangents, "VEC4")}
        g.add("meshes", {"primitives": [{"attributes": attrs, "indices": g.accessor(QUAD_I, "SCALAR", USHORT), "material": k}]})
        g.node(name=["lambert", "masked", "lamp"][k], mesh=k, translation=[3 * k, 0, 0])
    g.node(name="masked_mirror", mesh=1, scale=[-1, 1, 1], translation=[0, 0, 5])
    return g.finish()


def textured_room():
    """Every texture feature giq renders, in a small room with a view: an sRGB checker on the
    floor (bilinear, repeating), a normal-mapped wall with TANGENT and a metallic-roughness
    texture, an alpha-masked grating (nearest) under a lamp with an emissive texture, and a
    point light; vertex colours (COLOR_0) tint the wall and fade the grating's alpha. The
    real-time tests compare `pt` with `giq reference` on it."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_lights_punctual", "KHR_materials_emissive_strength"]

    def image(png):
        return g.add("images", {"uri": "data:image/png;base64," + base64.b64encode(png).decode()})

    def texture(png, sampler=None):
        t = {"source": image(png)}
        if sampler is not None:
            t["sampler"] = sampler
        return g.add("textures", t)

    linear_repeat = g.add("samplers", {"magFilter": 9729, "wrapS": 10497, "wrapT": 10497})
    nearest_clamp = g.add("samplers", {"magFilter": 9728, "wrapS": 33071, "wrapT": 33071})
    checker = png_rgba(4, 4, [[(200, 80, 40, 255) if (x + y) % 2 else (40, 90, 180, 255) for x in range(4)] for y in range(4)])
    ridges = []
    for x in range(8):
        tilt = 0.5 * math.sin(2 * math.pi * (x + 0.5) / 8)
        n = (tilt, 0.0, 1.0)
        length = math.sqrt(sum(c * c for c in n))
        ridges.append(tuple(int(round(255 * (0.5 * c / length + 0.5))) for c in n) + (255,))
    normal = png_rgba(8, 1, [ridges])
    rough = png_rgba(2, 2, [[(0, 90, 150, 255), (0, 230, 0, 255)], [(0, 230, 0, 255), (0, 90, 150, 255)]])
    stripes = png_rgba(6, 1, [[(230, 230, 230, 0 if x % 2 else 255) for x in range(6)]])
    tint = png_rgba(2, 2, [[(255, 255, 255, 255), (255, 160, 120, 255)], [(120, 200, 255, 255), (255, 255, 255, 255)]])
    floor_m = g.add("materials", {"name": "floor", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": texture(checker, linear_repeat)}, "metallicFactor": 0.0, "roughnessFactor": 0.8}})
    wall_m = g.add("materials", {"name": "wall", "normalTexture": {"index": texture(normal), "scale": 0.9},
                                 "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1.0],
                                                          "metallicRoughnessTexture": {"index": texture(rough, nearest_clamp)}}})
    grating_m = g.add("materials", {"name": "grating", "alphaMode": "MASK", "doubleSided": True, "pbrMetallicRoughness": {
        "baseColorTexture": {"index": texture(stripes, nearest_clamp)}, "metallicFactor": 0.0}})
    lamp_m = g.add("materials", {"name": "lamp", "emissiveFactor": [1.0, 1.0, 1.0],
                                 "emissiveTexture": {"index": texture(tint, nearest_clamp)},
                                 "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0]},
                                 "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 6.0}}})

    def quad(name, p, uvs, material, tangent=None, colors=None):
        a, b, c = p[0], p[1], p[2]
        e1 = [b[i] - a[i] for i in range(3)]
        e2 = [c[i] - a[i] for i in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        length = math.sqrt(sum(x * x for x in n))
        n = [x / length for x in n]
        attrs = {"POSITION": g.accessor(p, "VEC3", minmax=True), "NORMAL": g.accessor([n] * 4, "VEC3"),
                 "TEXCOORD_0": g.accessor(uvs, "VEC2")}
        if tangent:
            attrs["TANGENT"] = g.accessor([tangent] * 4, "VEC4")
        if colors:
            attrs["COLOR_0"] = g.accessor(colors, "VEC4")
        m = g.add("meshes", {"name": name, "primitives": [
            {"attributes": attrs, "indices": g.accessor([0, 1, 2, 0, 2, 3], "SCALAR", USHORT), "material": material}]})
        g.node(name=name, mesh=m)

    quad("floor", [(-1.5, 0, 1.5), (1.5, 0, 1.5), (1.5, 0, -1.5), (-1.5, 0, -1.5)], [(0, 2), (2, 2), (2, 0), (0, 0)], floor_m)
    quad("wall", [(-1.5, 0, -1.5), (1.5, 0, -1.5), (1.5, 2.5, -1.5), (-1.5, 2.5, -1.5)], [(0, 1), (1, 1), (1, 0), (0, 0)], wall_m,
         tangent=(1, 0, 0, 1), colors=[(1, 0.6, 0.6, 1), (0.6, 1, 0.6, 1), (0.6, 0.6, 1, 1), (1, 1, 1, 1)])
    quad("grating", [(-0.5, 1.2, 0.5), (0.5, 1.2, 0.5), (0.5, 1.2, -0.5), (-0.5, 1.2, -0.5)], [(0, 1), (1, 1), (1, 0), (0, 0)],
         grating_m, colors=[(1, 1, 1, 1), (1, 1, 1, 1), (1, 1, 1, 0.2), (1, 1, 1, 0.2)])
    quad("lamp", [(-0.4, 2.3, -0.4), (0.4, 2.3, -0.4), (0.4, 2.3, 0.4), (-0.4, 2.3, 0.4)], [(0, 0), (1, 0), (1, 1), (0, 1)], lamp_m)
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"name": "bulb", "type": "point", "intensity": 3.0}]}}
    g.node(name="bulb", translation=[0.8, 1.8, 0.6], extensions={"KHR_lights_punctual": {"light": 0}})
    d = g.finish()
    d["extras"] = {"giq": {"views": [{"name": "front", "eye": [0, 1.6, 3.2], "target": [0, 0.5, 0], "yfov_deg": 60}]}}
    return d


def external():
    g = Gltf()
    g.mesh("tri", TRI_P)
    g.node(name="tri", mesh=0)
    d = g.finish(external="external%20data.bin")
    with open(os.path.join(HERE, "external data.bin"), "wb") as f:
        f.write(bytes(g.bin))
    return d


def glb(doc_fn):
    """The same document as a .glb: JSON chunk + BIN chunk (glTF 2.0 spec, 4.4)."""
    g = Gltf()
    g.mesh("quad", QUAD_P, QUAD_I, QUAD_N)
    g.mesh("tri", TRI_P)
    g.node(name="quad", mesh=0, children=[1])
    g.node(name="tri", mesh=1, translation=[0, 0, 2])
    d = g.finish()
    d["buffers"] = [{"byteLength": len(g.bin)}]
    js = json.dumps(d).encode()
    js += b" " * (-len(js) % 4)
    body = struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(g.bin), 0x004E4942) + bytes(g.bin)
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def textured_glb():
    """A .glb whose PNG lives in the BIN chunk, reached through a buffer view."""
    g = Gltf()
    png = png_rgba(1, 2, [[(255, 0, 0, 255)], [(0, 0, 255, 255)]])
    g.add("images", {"bufferView": g.view(png), "mimeType": "image/png"})
    g.add("textures", {"source": 0})
    g.add("materials", {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})
    g.mesh("quad", QUAD_P, QUAD_I, QUAD_N, [(0, 0), (1, 0), (1, 1), (0, 1)], material=0)
    g.node(name="quad", mesh=0)
    d = g.finish()
    while len(g.bin) % 4:
        g.bin.append(0)
    d["buffers"] = [{"byteLength": len(g.bin)}]
    js = json.dumps(d).encode()
    js += b" " * (-len(js) % 4)
    body = struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(g.bin), 0x004E4942) + bytes(g.bin)
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def minimal(**patch):
    """One triangle, everything valid; `patch` then breaks exactly one thing."""
    g = Gltf()
    g.mesh("tri", TRI_P, [0, 1, 2])
    g.node(name="tri", mesh=0)
    d = g.finish()
    for fn in patch.values():
        fn(d, g)
    return d


# A Git LFS pointer (git-lfs's docs/spec.md) to a file that is not there.
LFS_POINTER = (b"version https://git-lfs.github.com/spec/v1\n"
               b"oid sha256:4d7a214614ab2935c943f9e0ff69d22eadbb8f32b1258daaa5e2ca24d17e2393\nsize 162852\n")


def hostile():
    cases = []  # (file name, expected field, content: dict = JSON, bytes = raw)

    def case(name, field, content):
        cases.append((name, field, content))

    def setp(path, value):
        def f(d, g):
            obj = d
            for k in path[:-1]:
                obj = obj[k]
            obj[path[-1]] = value
        return f

    tri_mesh_prim = ("meshes", 0, "primitives", 0)
    case("bad_json.gltf", "JSON", b'{"asset": {"version": "2.0"}, "nodes": [ {"name": "a",, } ]}\n')
    case("not_gltf2.gltf", "asset.version", {"asset": {"version": "1.0"}})
    # 30 000 nested arrays in extras: tinygltf's conversion of extras recurses once a level.
    case("deep_extras.gltf", "JSON", b'{"asset": {"version": "2.0"}, "extras": ' + b"[" * 30000 + b"]" * 30000 + b"}\n")
    case("duplicate_key.gltf", "asset.version", b'{"asset": {"version": "2.0", "version": "2.0"}}\n')
    case("missing_buffer.gltf", "buffers[0].uri", minimal(a=setp(("buffers", 0, "uri"), "missing.bin")))
    case("absolute_uri.gltf", "buffers[0].uri", minimal(a=setp(("buffers", 0, "uri"), "/etc/passwd")))
    case("escaping_uri.gltf", "buffers[0].uri", minimal(a=setp(("buffers", 0, "uri"), "../hostile/../../scenes/external%20data.bin")))
    case("symlink_escape.gltf", "buffers[0].uri", minimal(a=setp(("buffers", 0, "uri"), "outside.bin")))
    case("http_uri.gltf", "buffers[0].uri", minimal(a=setp(("buffers", 0, "uri"), "http://example.com/a.bin")))
    case("bad_data_uri.gltf", "buffers[0].uri", minimal(a=setp(("buffers", 0, "uri"), "data:application/octet-stream;base64,AAA*AAAA")))
    # A buffer without data may only stand behind compressed views (EXT_meshopt_compression).
    case("placeholder_buffer.gltf", "bufferViews[0].buffer", minimal(a=lambda d, g: d["buffers"][0].pop("uri")))
    case("meshopt_mode.gltf", "bufferViews[0].extensions.EXT_meshopt_compression.mode",
         minimal(a=setp(("bufferViews", 0, "extensions"), {"EXT_meshopt_compression": {
             "buffer": 0, "byteLength": 4, "byteStride": 12, "count": 3, "mode": "POINTS"}})))
    case("absurd_size.gltf", "buffers[0].byteLength", minimal(a=setp(("buffers", 0, "byteLength"), 1000000000)))
    case("view_exceeds_buffer.gltf", "bufferViews[0]", minimal(a=setp(("bufferViews", 0, "byteLength"), 4096)))
    case("accessor_exceeds_view.gltf", "accessors[0]", minimal(a=setp(("accessors", 0, "count"), 40)))
    case("accessor_out_of_range.gltf", "meshes[0].primitives[0].attributes.POSITION",
         minimal(a=setp(tri_mesh_prim + ("attributes", "POSITION"), 7)))
    def huge_zeros(d, g):
        del d["accessors"][0]["bufferView"]
        d["accessors"][0]["count"] = 4000000000
    case("huge_count.gltf", "accessors[0].count", minimal(a=huge_zeros))
    def instancing_bomb(d, g):
        # A sparse accessor over 2^20 - 1 implicit zeros: 349525 (degenerate) triangles from a few
        # bytes, instanced by 400 nodes.
        g2 = Gltf()
        sp = {"count": 1, "indices": {"bufferView": g2.view(struct.pack("<H", 1)), "componentType": USHORT},
              "values": {"bufferView": g2.view(struct.pack("<3f", 1, 0, 0))}}
        d["accessors"] = [{"componentType": FLOAT, "count": (1 << 20) - 1, "type": "VEC3", "sparse": sp}]
        d["bufferViews"] = g2.doc["bufferViews"]
        d["buffers"] = [{"byteLength": len(g2.bin), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(g2.bin)).decode()}]
        d["meshes"] = [{"primitives": [{"attributes": {"POSITION": 0}}]}]
        d["nodes"] = [{"mesh": 0} for _ in range(400)]
        d["scenes"] = [{"nodes": list(range(400))}]
    per_node = ((1 << 20) - 1) // 3
    case("instancing_bomb.gltf", "nodes[%d].mesh" % ((1 << 25) // per_node), minimal(a=instancing_bomb))
    case("wrong_component_type.gltf", "accessors[0].componentType", minimal(a=setp(("accessors", 0, "componentType"), USHORT)))
    case("wrong_type.gltf", "accessors[0].type", minimal(a=setp(("accessors", 0, "type"), "VEC2")))
    case("index_wrong_type.gltf", "accessors[1].componentType", minimal(a=setp(("accessors", 1, "componentType"), FLOAT)))

    def bad_index(d, g):
        # Third index 9 with only 3 vertices.
        g2 = Gltf()
        g2.accessor(TRI_P, "VEC3", minmax=True)
        g2.accessor([0, 1, 9], "SCALAR", USHORT)
        d["bufferViews"], d["accessors"] = g2.doc["bufferViews"], g2.doc["accessors"]
        d["buffers"] = [{"byteLength": len(g2.bin), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(g2.bin)).decode()}]
    case("index_out_of_range.gltf", "meshes[0].primitives[0].indices", minimal(a=bad_index))

    def nan_position(d, g):
        g2 = Gltf()
        g2.accessor([(0, 0, 0), (float("nan"), 0, 0), (0, 1, 0)], "VEC3")
        g2.accessor([0, 1, 2], "SCALAR", USHORT)
        d["bufferViews"], d["accessors"] = g2.doc["bufferViews"], g2.doc["accessors"]
        d["buffers"] = [{"byteLength": len(g2.bin), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(g2.bin)).decode()}]
    case("nan_position.gltf", "accessors[0]", minimal(a=nan_position))

    def cycle(d, g):
        d["nodes"] = [{"name": "a", "children": [1]}, {"name": "b", "children": [0], "mesh": 0}]
        d["scenes"] = [{"nodes": []}]
    case("node_cycle.gltf", "nodes[0].children", minimal(a=cycle))

    def two_parents(d, g):
        d["nodes"] = [{"children": [2]}, {"children": [2]}, {"mesh": 0}]
        d["scenes"] = [{"nodes": [0, 1]}]
    case("two_parents.gltf", "nodes[1].children", minimal(a=two_parents))
    inf = json.dumps(minimal(a=setp(("nodes", 0, "translation"), [0, "INF", 0]))).replace('"INF"', "1e400")
    case("inf_translation.gltf", "JSON", (inf + "\n").encode())  # JSON itself cannot hold NaN or Inf

    def overflow(d, g):
        d["nodes"] = [{"scale": [1e300] * 3, "children": [1]}, {"scale": [1e300] * 3, "mesh": 0}]
        d["scenes"] = [{"nodes": [0]}]
    case("overflowing_transform.gltf", "nodes", minimal(a=overflow))
    case("bad_child.gltf", "nodes[0].children", minimal(a=setp(("nodes", 0, "children"), [5])))
    case("unsupported_extension.gltf", "extensionsRequired[0]",
         minimal(a=setp(("extensionsRequired",), ["KHR_materials_transmission"]), b=setp(("extensionsUsed",), ["KHR_materials_transmission"])))

    def texture(uri_bytes, tex_coord=0, ext=None):
        def f(d, g):
            d["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(uri_bytes).decode()}]
            d["textures"] = [{"source": 0}]
            info = {"index": 0}
            if tex_coord:
                info["texCoord"] = tex_coord
            if ext:
                info["extensions"] = ext
            d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": info}}]
            d["meshes"][0]["primitives"][0]["material"] = 0
        return f
    good_png = png_rgba(1, 1, [[(255, 255, 255, 255)]])
    case("bad_texture.gltf", "images[0]", minimal(a=texture(b"\x89PNG\r\n\x1a\n this is not an image")))
    def three_uv_mappings(d, g):
        d["materials"][0]["normalTexture"] = {"index": 0, "texCoord": 1}
        d["materials"][0]["emissiveTexture"] = {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0]}}}
    case("three_uv_mappings.gltf", "materials[0].emissiveTexture", minimal(a=texture(good_png), b=three_uv_mappings))
    case("bad_texture_transform.gltf", "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.scale",
         minimal(a=texture(good_png, ext={"KHR_texture_transform": {"scale": [2]}})))

    def camera(kind):
        def f(d, g):
            if kind == "orthographic":
                d["cameras"] = [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 0.1}}]
            d["nodes"][0]["camera"] = 0
        return f
    case("orthographic_depth.gltf", "cameras[0].orthographic.zfar", minimal(a=camera("orthographic")))
    case("alpha_mode.gltf", "materials[0].alphaMode",
         minimal(a=setp(("materials",), [{"alphaMode": "ADD"}]), b=setp(tri_mesh_prim + ("material",), 0)))
    # A skinned node whose mesh has no JOINTS_0.
    case("skin.gltf", "meshes[0].primitives[0].attributes.JOINTS_0", minimal(a=setp(("skins",), [{"joints": [0]}]), b=setp(("nodes", 0, "skin"), 0)))
    case("skin_bad_joint.gltf", "skins[0].joints", minimal(a=setp(("skins",), [{"joints": [7]}]), b=setp(("nodes", 0, "skin"), 0)))
    case("skin_missing.gltf", "nodes[0].skin", minimal(a=setp(("nodes", 0, "skin"), 0)))
    # One target, two weights.
    case("morph.gltf", "nodes[0].weights",
         minimal(a=setp(tri_mesh_prim + ("targets",), [{"POSITION": 0}]), b=setp(("nodes", 0, "weights"), [0.5, 0.5])))
    # The target names the SCALAR index accessor.
    case("morph_target_type.gltf", "accessors[1].type", minimal(a=setp(tri_mesh_prim + ("targets",), [{"POSITION": 1}])))
    case("area_light_shape.gltf", "meshes[0].extras.giq.area_light",
         minimal(a=setp(("meshes", 0, "extras"), {"giq": {"area_light": "cylinder"}})))
    case("area_light_key.gltf", "meshes[0].extras.giq.area", minimal(a=setp(("meshes", 0, "extras"), {"giq": {"area": "disc"}})))
    case("unknown_mode.gltf", "meshes[0].primitives[0].mode", minimal(a=setp(tri_mesh_prim + ("mode",), 7)))

    def anim(path, times=(0.0, 1.0)):
        def f(d, g):
            g2 = Gltf()
            g2.bin = bytearray(base64.b64decode(d["buffers"][0]["uri"].split(",", 1)[1]))
            g2.doc["bufferViews"], g2.doc["accessors"] = d["bufferViews"], d["accessors"]
            t = g2.accessor(list(times), "SCALAR", minmax=True)
            o = g2.accessor([1.0, 1.0], "SCALAR") if path == "weights" else g2.accessor([(0, 0, 0), (1, 0, 0)], "VEC3")
            d["buffers"] = [{"byteLength": len(g2.bin), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(g2.bin)).decode()}]
            d["animations"] = [{"samplers": [{"input": t, "output": o}], "channels": [{"sampler": 0, "target": {"node": 0, "path": path}}]}]
        return f
    # Weights animated on a node whose mesh has no morph targets.
    case("weights_animation.gltf", "animations[0].channels[0].target.node", minimal(a=anim("weights")))
    case("decreasing_keys.gltf", "accessors[2]", minimal(a=anim("translation", (1.0, 0.5))))

    def extras(giq):
        return setp(("extras",), {"giq": giq})
    view = {"name": "v", "eye": [0, 0, 3], "target": [0, 0, 0]}
    case("extras_unknown_key.gltf", "extras.giq.veiws", minimal(a=extras({"veiws": [view]})))
    case("extras_unknown_view_key.gltf", "extras.giq.views[0].fov", minimal(a=extras({"views": [dict(view, fov=40)]})))
    case("extras_duplicate_view.gltf", "extras.giq.views[1].name", minimal(a=extras({"views": [view, view]})))
    case("extras_bad_eye.gltf", "extras.giq.views[0].eye", minimal(a=extras({"views": [dict(view, eye=[0, 0])]})))
    case("extras_unknown_leak_region.gltf", "extras.giq.leak_regions[0]", minimal(a=extras({"leak_regions": ["nowhere"]})))
    case("extras_unknown_animation.gltf", "extras.giq.sequence.animation", minimal(a=extras({"sequence": {"animation": "walk"}})))
    seq = {"frames": 60, "step_frame": 30, "flicker_frames": "12:27", "lag_frames": "28:43"}
    case("extras_late_step.gltf", "extras.giq.sequence.step_frame", minimal(a=extras({"sequence": dict(seq, step_frame=60)})))
    case("extras_bad_window.gltf", "extras.giq.sequence.flicker_frames", minimal(a=extras({"sequence": dict(seq, flicker_frames=[12, 27])})))
    case("extras_window_past_end.gltf", "extras.giq.sequence.lag_frames", minimal(a=extras({"sequence": dict(seq, lag_frames="28:60")})))
    case("extras_flicker_across_step.gltf", "extras.giq.sequence.flicker_frames", minimal(a=extras({"sequence": dict(seq, flicker_frames="12:30")})))
    case("extras_lag_without_step.gltf", "extras.giq.sequence.lag_frames",
         minimal(a=extras({"sequence": {"frames": 60, "lag_frames": "28:43"}})))
    case("extras_lag_after_step.gltf", "extras.giq.sequence.lag_frames", minimal(a=extras({"sequence": dict(seq, lag_frames="30:43")})))
    emitter = {"name": "e", "node": "tri", "rate": 10, "lifetime": 1}
    case("emitter_unknown_node.gltf", "extras.giq.emitters[0].node", minimal(a=extras({"emitters": [dict(emitter, node="nozzle")]})))
    case("emitter_no_rate.gltf", "extras.giq.emitters[0].rate", minimal(a=extras({"emitters": [{"name": "e", "node": "tri"}]})))
    case("emitter_capacity.gltf", "extras.giq.emitters[0].max_particles", minimal(a=extras({"emitters": [dict(emitter, max_particles=5)]})))
    case("emitter_strength.gltf", "extras.giq.emitters[0].strength[1][0]",
         minimal(a=extras({"emitters": [dict(emitter, strength=[[0.5, 1], [0.2, 0]])]})))
    case("emitter_key.gltf", "extras.giq.emitters[0].velocity", minimal(a=extras({"emitters": [dict(emitter, velocity=[0, 1, 0])]})))
    case("emitter_too_many.gltf", "extras.giq.emitters[0].rate", minimal(a=extras({"emitters": [dict(emitter, rate=1e7, lifetime=10)]})))

    tri_glb = glb(None)
    case("truncated.glb", "glb header.length", tri_glb[: len(tri_glb) // 2])
    bad_chunk = bytearray(tri_glb)
    struct.pack_into("<I", bad_chunk, 12, 1 << 30)  # JSON chunk length far beyond the file
    case("bad_chunk.glb", "glb chunk[0].chunkLength", bytes(bad_chunk))

    # What arrives in place of a model: nothing, a Git LFS pointer (a clone without its LFS
    # objects), a web page, another format under the model's name.
    case("empty.glb", "glb header.magic", b"")
    case("lfs_pointer.glb", "glb header.magic", LFS_POINTER)
    case("html_page.gltf", "JSON", b'<!DOCTYPE html>\n<html lang="en">\n<head><title>Not Found</title></head>\n<body>404</body>\n</html>\n')
    case("zip_named_glb.glb", "glb header.magic", b"PK\x03\x04\x14\x00\x00\x00")
    case("lfs_buffer.gltf", "buffers[0].byteLength", minimal(a=setp(("buffers", 0, "uri"), "lfs_buffer.bin")))
    case("lfs_texture.gltf", "images[0]", minimal(a=texture(LFS_POINTER)))
    return cases


def main():
    write(os.path.join(HERE, "transforms.gltf"), transforms())
    write(os.path.join(HERE, "strip_fan.gltf"), strip_fan())
    write(os.path.join(HERE, "textured.gltf"), textured())
    write(os.path.join(HERE, "animated.gltf"), animated())
    write(os.path.join(HERE, "skinned.gltf"), skinned())
    write(os.path.join(HERE, "morphed.gltf"), morphed())
    write(os.path.join(HERE, "collapsing.gltf"), collapsing())
    write(os.path.join(HERE, "area_shapes.gltf"), area_shapes())
    write(os.path.join(HERE, "fountain.gltf"), fountain())
    write(os.path.join(HERE, "lights_cameras.gltf"), lights_cameras())
    write(os.path.join(HERE, "materials.gltf"), materials())
    write(os.path.join(HERE, "textured_room.gltf"), textured_room())
    write(os.path.join(HERE, "uv_sets.gltf"), uv_sets())
    write(os.path.join(HERE, "two_uv_sets.gltf"), two_uv_sets())
    write(os.path.join(HERE, "extensions.gltf"), extensions())
    write(os.path.join(HERE, "instancing.gltf"), instancing())
    write(os.path.join(HERE, "external.gltf"), external())
    with open(os.path.join(HERE, "quad_tri.glb"), "wb") as f:
        f.write(glb(None))
    with open(os.path.join(HERE, "textured.glb"), "wb") as f:
        f.write(textured_glb())
    os.makedirs(HOSTILE, exist_ok=True)
    lines = ["# hostile file\tglTF path the error must name (tests/scenes/hostile_test.cpp, tests/cli)"]
    for name, field, content in hostile():
        path = os.path.join(HOSTILE, name)
        if isinstance(content, dict):
            write(path, content)
        else:
            with open(path, "wb") as f:
                f.write(content)
        lines.append(name + "\t" + field)
    # outside.bin points out of hostile/ at a real buffer: a symlink escape.
    link = os.path.join(HOSTILE, "outside.bin")
    if os.path.lexists(link):
        os.remove(link)
    os.symlink("../external data.bin", link)
    with open(os.path.join(HOSTILE, "lfs_buffer.bin"), "wb") as f:
        f.write(LFS_POINTER)
    with open(os.path.join(HOSTILE, "expected.tsv"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
