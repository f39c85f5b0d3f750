"""pip install . into a fresh virtual environment, as docs/python.md tells a user to, reusing
this build's CMake folder (GIQ_CMAKE_BUILD_DIR) so that it costs seconds; then the installed
package, away from the source and build trees, reads, scores and reads a PNG screenshot."""

import os
import subprocess
import sys

import numpy as np

import giq
from conftest import SOURCE


def test_pip_install_gives_a_working_package(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    env = dict(os.environ, GIQ_CMAKE_BUILD_DIR=os.environ.get("GIQ_BUILD_DIR", str(SOURCE / "build" / "default")))
    env.pop("PYTHONPATH", None)
    r = subprocess.run([str(venv / "bin" / "pip"), "install", "--no-build-isolation", "--no-deps", "--no-index", "-q",
                        str(SOURCE)], env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    a = np.linspace(0.0, 2.0, 8 * 8 * 3, dtype=np.float32).reshape(8, 8, 3)
    giq.write_exr(tmp_path / "ref.exr", {"beauty": a})
    screenshot = tmp_path / "shot.png"
    # A PNG to read through the OpenImageIO module the package carries: giq writes one in every score.
    giq.score(a, a * 0.5, out=tmp_path / "maps")
    os.replace(tmp_path / "maps" / "abs_error.png", screenshot)
    script = f"""
import giq, numpy as np
assert giq.__file__.startswith({str(venv)!r}), giq.__file__
ref = giq.read_exr({str(tmp_path / 'ref.exr')!r})
m = giq.score(ref, ref['beauty'] * 0.5)
print(m['metrics']['relmse']['value'])
print(giq.score({str(tmp_path / 'ref.exr')!r}, {str(screenshot)!r})['inputs']['dynamic_range'])
"""
    out = subprocess.run([str(venv / "bin" / "python"), "-c", script], env=env, cwd=tmp_path, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    relmse, dynamic_range = out.stdout.split()
    assert float(relmse) == giq.relmse(a, a * 0.5)
    assert dynamic_range == "ldr"
