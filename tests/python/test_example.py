"""docs/examples/python/error_vs_time.py, the example of docs/python.md, runs as the page says and
finds what the Cornell box must show: direct light alone is too dark, a path tracer is not."""

import json
import subprocess
import sys

from conftest import SOURCE


def test_the_error_against_time_example_runs(tmp_path):
    r = subprocess.run([sys.executable, str(SOURCE / "docs" / "examples" / "python" / "error_vs_time.py"), "--size", "32",
                        "--spp", "64", "--frames", "2", "--technique", "direct", "--technique", "pt", "--out", str(tmp_path)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    rows = {row["technique"]: row for row in json.loads((tmp_path / "rows.json").read_text())}
    assert sorted(rows) == ["direct", "pt"]
    assert all(row["gpu_ms"] > 0.0 and row["relmse"] > 0.0 for row in rows.values())
    # Indirect light is about a quarter of what the front view sees (direct alone gives 0.77 of
    # the reference's mean luminance); the reference's mean at 64 spp over 1024 pixels is good
    # to well under 1 %, and pt's two frames to a few per cent.
    assert rows["direct"]["mean_luminance_ratio"] < 0.85
    assert abs(rows["pt"]["mean_luminance_ratio"] - 1.0) < 0.15
    assert (tmp_path / "reference.exr").exists()
