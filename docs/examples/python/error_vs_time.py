"""Error against GPU time from Python: renders a scene's reference, runs real-time techniques on
the same view, scores each against the reference and plots relMSE over milliseconds (with
matplotlib, when it is installed). docs/python.md walks through it.

    python3 docs/examples/python/error_vs_time.py --technique direct --technique ddgi --out out/python
"""

import argparse
import json
import math
from pathlib import Path

import giq

SCENES = Path(__file__).resolve().parents[3] / "scenes"


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scene", default=str(SCENES / "cornell.gltf"))
    p.add_argument("--view", default=None)
    p.add_argument("--size", type=int, default=128, help="image width and height in pixels")
    p.add_argument("--spp", type=int, default=1024, help="reference samples per pixel")
    p.add_argument("--frames", type=int, default=16, help="frames each technique renders; the last is scored")
    p.add_argument("--technique", action="append", help="repeatable (default: every technique)")
    p.add_argument("--out", default="out/python")
    args = p.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    scene = giq.Scene(args.scene)
    print(scene)
    ref = giq.reference(scene, view=args.view, spp=args.spp, width=args.size, height=args.size,
                        progress=lambda p: print(f"\r  reference {p['spp']}/{p['target_spp']} spp", end="", flush=True))
    print()
    giq.write_exr(out / "reference.exr", ref, ref.metadata)

    techniques = args.technique or [t["name"] for t in giq.techniques()["techniques"]]
    rows = []
    for name in techniques:
        # Frames 0..n-2 warm the technique's caches and history up; the last one is measured.
        frames, timings = giq.realtime(scene, name, view=args.view, frames=(args.frames - 1, args.frames - 1),
                                       width=args.size, height=args.size)
        m = giq.score(ref, frames[-1])["metrics"]
        rows.append({"technique": name, "gpu_ms": timings["frame_gpu_ms"]["median"], "device": timings["device"]["name"],
                     "relmse": m["relmse"]["value"], "flip": m["flip"]["mean"]["value"],
                     "mean_luminance_ratio": m["mean_luminance_ratio"]})

    print(f"{'technique':<10} {'GPU ms':>9} {'relMSE':>9} {'FLIP':>7} {'Y_T/Y_R':>8}")
    for r in rows:
        print(f"{r['technique']:<10} {r['gpu_ms']:>9.3f} {r['relmse']:>9.4f} {r['flip']:>7.4f} {r['mean_luminance_ratio']:>8.3f}")
    (out / "rows.json").write_text(json.dumps(rows, indent=2) + "\n")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plot (apt install python3-matplotlib)")
        return
    fig, ax = plt.subplots(figsize=(6, 4))
    for r in rows:
        ax.scatter(r["gpu_ms"], r["relmse"])
        ax.annotate(r["technique"], (r["gpu_ms"], r["relmse"]), textcoords="offset points", xytext=(4, 4))
    ax.set_xlabel(f"GPU time per frame (ms, {rows[0]['device']})")
    ax.set_ylabel("relMSE against the reference")
    ax.set_yscale("log")
    if all(r["gpu_ms"] > 0 and math.isfinite(r["gpu_ms"]) for r in rows):
        ax.set_xscale("log")
    fig.tight_layout()
    fig.savefig(out / "error_vs_time.png", dpi=120)
    print(f"plot: {out / 'error_vs_time.png'}")


if __name__ == "__main__":
    main()
