"""Shared fixtures of the Python module's tests: the giq binary they compare with, the built-in
scenes, and small images rendered once per session."""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import giq

SOURCE = Path(os.environ.get("GIQ_SOURCE_DIR", Path(__file__).resolve().parents[2]))
SCENES = SOURCE / "scenes"
CLI = os.environ.get("GIQ_CLI", str(SOURCE / "build" / "default" / "tools" / "giq"))


def run_cli(*args, check=True):
    """Runs the giq command line; returns the completed process (stdout and stderr as text)."""
    r = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError(f"giq {' '.join(map(str, args))} exited {r.returncode}: {r.stderr}")
    return r


def cli_error(*args):
    """The one-line message giq prints for an input error (exit 2), without its 'giq: error: '."""
    r = run_cli(*args, check=False)
    assert r.returncode == 2, r.stderr
    line = r.stderr.strip().splitlines()[-1]
    assert line.startswith("giq: error: ")
    return line[len("giq: error: "):]


def equal_nan(a, b):
    """JSON-like values equal, NaN equal to NaN."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(equal_nan(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(equal_nan(x, y) for x, y in zip(a, b))
    if isinstance(a, float) and isinstance(b, float) and np.isnan(a) and np.isnan(b):
        return True
    return a == b


@pytest.fixture(scope="session")
def renders(tmp_path_factory):
    """A 32x24 reference of the Cornell box (with its variance) and two real-time renders of
    it, as EXR files: direct (too dark: no indirect light) and pt."""
    d = tmp_path_factory.mktemp("renders")
    run_cli("reference", "--scene", SCENES / "cornell.gltf", "--spp", 64, "--width", 32, "--height", 24,
            "--out", d / "ref.exr")
    for technique in ("direct", "pt"):
        run_cli("realtime", "--scene", SCENES / "cornell.gltf", "--technique", technique, "--width", 32,
                "--height", 24, "--out", d / technique)
    return {"ref": d / "ref.exr", "direct": d / "direct" / "frame_0000.exr", "pt": d / "pt" / "frame_0000.exr",
            "dir": d}


def read_json(path):
    with open(path) as f:
        return json.load(f)
