"""giq.Scene, giq.reference, giq.realtime and giq.techniques against the command line: the same
scene description, the same bits for the same settings, progress, Ctrl-C and the GIL."""

import json
import os
import signal
import threading
import time

import numpy as np
import pytest

import giq
from conftest import SCENES, cli_error, run_cli

CORNELL = SCENES / "cornell.gltf"


def assert_same_layers(a, b):
    assert sorted(a) == sorted(b)
    for name in a:
        assert np.array_equal(a[name], b[name], equal_nan=True), name


def test_scene_info_is_giq_scene_info():
    s = giq.Scene(CORNELL)
    assert s.info == json.loads(run_cli("scene", "info", CORNELL, "--json").stdout)
    assert s.views == ["front", "corner"] and s.frames == 1 and s.path == str(CORNELL)
    # sun= and env= as giq's --sun and --env.
    lit = giq.Scene(CORNELL, sun="dir=0,-1,0 illuminance=3", env=(0.1, 0.2, 0.3)).info
    assert {"name": "sun", "type": "directional", "intensity": 3.0}.items() <= lit["lights"][0].items()
    assert lit["environment_radiance"] == pytest.approx([0.1, 0.2, 0.3], rel=1e-7)
    with pytest.raises(ValueError, match="--env: '1.0,-1.0,1.0' must be finite and not negative"):
        giq.Scene(CORNELL, env=[1, -1, 1])
    moving = giq.Scene(SCENES / "movinglight.gltf")
    assert moving.frames == moving.info["sequence"]["frames"] > 1


def test_a_reference_from_python_is_the_command_lines_bit_for_bit(tmp_path):
    run_cli("reference", "--scene", CORNELL, "--view", "corner", "--spp", 8, "--width", 24, "--height", 16, "--seed", 3,
            "--out", tmp_path / "cli.exr")
    got = giq.reference(giq.Scene(CORNELL), view="corner", spp=8, width=24, height=16, seed=3)
    cli = giq.read_exr(tmp_path / "cli.exr")
    assert_same_layers(got, cli)
    assert got.metadata == cli.metadata and got.channels == cli.channels
    # A camera as --camera gives it, the scene as a path.
    camera = "eye=0.2,1,3.5 target=0,0.9,0 fov=50"
    run_cli("reference", "--scene", CORNELL, "--camera", camera, "--spp", 4, "--width", 16, "--height", 16,
            "--out", tmp_path / "cam.exr")
    assert_same_layers(giq.reference(CORNELL, camera=camera, spp=4, width=16, height=16),
                       giq.read_exr(tmp_path / "cam.exr"))


def test_reference_progress_reaches_its_target():
    seen = []
    giq.reference(CORNELL, spp=64, width=16, height=16, progress=seen.append)
    assert seen and seen[-1]["spp"] == 64 and seen[-1]["target_spp"] == 64
    assert all(a["spp"] <= b["spp"] for a, b in zip(seen, seen[1:]))
    # An exception in the callback stops the render and reaches the caller.
    def fail(p):
        raise RuntimeError("stop here")
    with pytest.raises(RuntimeError, match="stop here"):
        giq.reference(CORNELL, rel_error=1e-9, width=16, height=16, progress=fail)


def test_ctrl_c_stops_a_long_render_and_other_threads_run_meanwhile():
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.01)

    counter = threading.Thread(target=count)
    counter.start()
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            giq.reference(CORNELL, rel_error=1e-12, width=64, height=64)  # hours, were it not stopped
    finally:
        stop.set()
        counter.join()
        timer.cancel()
    # The render held no GIL: the counting thread ran ~100 times a second throughout. It stops
    # at its next pass, well within seconds of the signal.
    assert len(ticks) > 40
    assert time.monotonic() - start < 20.0


def test_bad_render_arguments_raise_the_command_lines_messages(tmp_path):
    with pytest.raises(ValueError) as e:
        giq.reference(CORNELL, view="nowhere", spp=1)
    assert str(e.value) == cli_error("reference", "--scene", CORNELL, "--view", "nowhere", "--spp", 1, "--out", tmp_path / "x.exr")
    with pytest.raises(ValueError) as e:
        giq.realtime(CORNELL, "nope")
    assert str(e.value) == cli_error("realtime", "--scene", CORNELL, "--technique", "nope", "--out", tmp_path / "rt")
    with pytest.raises(ValueError, match="camera"):
        giq.reference(CORNELL, camera="eye=0,1,2", spp=1)
    with pytest.raises(ValueError, match="no stopping criterion"):
        giq.reference(CORNELL)
    with pytest.raises(ValueError) as e:
        giq.Scene(tmp_path / "missing.gltf")
    assert str(e.value) == cli_error("scene", "info", tmp_path / "missing.gltf")


def test_a_realtime_render_from_python_is_the_command_lines(tmp_path):
    run_cli("realtime", "--scene", CORNELL, "--technique", "pt", "--param", "samples_per_frame=2", "--frames", 2,
            "--width", 24, "--height", 16, "--out", tmp_path / "cli")
    calls = []
    frames, timings = giq.realtime(CORNELL, "pt", params={"samples_per_frame": 2}, frames=2, width=24, height=16,
                                   progress=lambda done, total: calls.append((done, total)))
    assert len(frames) == 2
    for i, f in enumerate(frames):
        assert_same_layers(f, giq.read_exr(tmp_path / "cli" / f"frame_{i:04d}.exr"))
    cli_timings = json.loads((tmp_path / "cli" / "timings.json").read_text())
    assert timings.keys() == cli_timings.keys() and timings["technique"] == cli_timings["technique"]
    assert timings["frames"]["measured"] == 2 and timings["frame_gpu_ms"]["median"] > 0.0
    assert calls and calls[-1] == (2, 2)


def test_techniques_is_the_listing_of_the_command_line():
    assert giq.techniques() == json.loads(run_cli("realtime", "--list", "--json").stdout)
