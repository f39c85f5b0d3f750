#!/usr/bin/env python3
"""Writes a scene whose file does not move but whose particles do: the built-in `dynamic`
with its animation left out (the walker stands still) and a still heightfield of
2 N^2 triangles (N = 708: about a million) under its room, for timing what a frame costs the
host when only the particles move (bench/results/particle-host-amd-epyc-2vcpu.md). With
--walking the animation stays: a skinned walker in a still level of a million triangles,
for what a frame costs when a few meshes of a large file move.

    python3 bench/scenes/static_fountain.py OUT.gltf [N] [--walking]

Deterministic: the same N gives the same bytes."""

import base64
import json
import math
import os
import struct
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def main():
    args = [a for a in sys.argv[1:] if a != "--walking"]
    walking = len(args) < len(sys.argv) - 1
    out = args[0]
    n = int(args[1]) if len(args) > 1 else 708
    with open(os.path.join(ROOT, "scenes", "dynamic.gltf")) as f:
        d = json.load(f)
    if not walking:
        d["extras"]["giq"]["sequence"] = {"frames": 60, "fps": 30.0, "animation": -1}
        d.pop("animations", None)
    positions = []
    for j in range(n + 1):
        for i in range(n + 1):
            x, z = -20.0 + 40.0 * i / n, -20.0 + 40.0 * j / n
            positions.append((x, -0.5 - 0.2 * math.sin(1.3 * x) * math.cos(0.7 * z), z))
    indices = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c = a + 1, a + n + 1
            indices += [a, c, b, b, c, c + 1]
    pb = b"".join(struct.pack("<3f", *p) for p in positions)
    ib = struct.pack("<%dI" % len(indices), *indices)
    buffer = len(d["buffers"])
    d["buffers"].append({"byteLength": len(pb) + len(ib),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(pb + ib).decode()})
    view = len(d["bufferViews"])
    d["bufferViews"] += [{"buffer": buffer, "byteOffset": 0, "byteLength": len(pb), "target": 34962},
                         {"buffer": buffer, "byteOffset": len(pb), "byteLength": len(ib), "target": 34963}]
    accessor = len(d["accessors"])
    d["accessors"] += [{"bufferView": view, "componentType": 5126, "count": len(positions), "type": "VEC3",
                        "min": [min(p[k] for p in positions) for k in range(3)],
                        "max": [max(p[k] for p in positions) for k in range(3)]},
                       {"bufferView": view + 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"}]
    d["meshes"].append({"name": "terrain", "primitives": [{"attributes": {"POSITION": accessor}, "indices": accessor + 1, "material": 0}]})
    d["nodes"].append({"name": "terrain", "mesh": len(d["meshes"]) - 1})
    d["scenes"][d.get("scene", 0)]["nodes"].append(len(d["nodes"]) - 1)
    with open(out, "w") as f:
        json.dump(d, f)
    print("%s: %d triangles added" % (out, len(indices) // 3))


if __name__ == "__main__":
    main()
