"""giq.score and the single metrics against giq score on the same data: the same JSON, the same
FLIP map bit for bit, the same numbers whatever the arrays' layout, and the same errors."""

import json

import numpy as np
import pytest

import giq
from conftest import cli_error, equal_nan, read_json, run_cli


def test_score_with_out_is_giq_score(tmp_path, renders):
    cli_out, py_out = tmp_path / "cli", tmp_path / "py"
    run_cli("score", "--ref", renders["ref"], "--test", renders["direct"], "--out", cli_out)
    got = giq.score(str(renders["ref"]), renders["direct"], out=py_out)  # str and PathLike alike
    cli = read_json(cli_out / "metrics.json")
    assert equal_nan(json.loads(json.dumps(got)), cli)
    assert read_json(py_out / "metrics.json") == cli
    assert sorted(p.name for p in py_out.iterdir()) == sorted(p.name for p in cli_out.iterdir())


def test_arrays_score_as_the_files_that_hold_them(tmp_path, renders):
    run_cli("score", "--ref", renders["ref"], "--test", renders["pt"], "--out", tmp_path / "cli")
    cli = read_json(tmp_path / "cli" / "metrics.json")
    ref, test = giq.read_exr(renders["ref"]), giq.read_exr(renders["pt"])
    # The layers as read_exr gives them (variance and objectId included), and the bare arrays.
    for got in (giq.score(ref, test),
                giq.score(ref["beauty"], test["beauty"], variance=ref["variance"], object_id=ref["objectId"])):
        assert equal_nan(got["metrics"], cli["metrics"])
        assert got["warnings"] == cli["warnings"]
        assert "maps" not in got and "strip" not in got  # nothing written without out=
    # Another layer, as --layer indirect.
    run_cli("score", "--ref", renders["ref"], "--test", renders["pt"], "--layer", "indirect", "--out", tmp_path / "ind")
    assert equal_nan(giq.score(ref, test, layer="indirect")["metrics"], read_json(tmp_path / "ind" / "metrics.json")["metrics"])


def test_layout_and_width_of_the_arrays_do_not_change_a_score(renders):
    ref = giq.read_exr(renders["ref"])["beauty"]
    # Values exact in float16, so every width holds the same numbers.
    test = (ref * 0.9).astype(np.float16).astype(np.float32)
    base = giq.score(ref, test)["metrics"]
    for variant in (np.asfortranarray(test), test.astype(np.float64), test.astype(np.float16), test[::-1][::-1]):
        assert equal_nan(giq.score(ref, variant)["metrics"], base)
    # A grey (H, W) array is the RGB image with three equal channels.
    grey = ref[..., 1].copy()
    assert equal_nan(giq.score(grey, grey * 0.5)["metrics"],
                     giq.score(np.repeat(grey[..., None], 3, 2), np.repeat(grey[..., None] * 0.5, 3, 2))["metrics"])


def test_flip_is_giq_scores_flip_bit_for_bit(tmp_path, renders):
    run_cli("score", "--ref", renders["ref"], "--test", renders["direct"], "--out", tmp_path / "cli")
    cli = read_json(tmp_path / "cli" / "metrics.json")
    mean, flip_map = giq.flip(giq.read_exr(renders["ref"])["beauty"], giq.read_exr(renders["direct"])["beauty"])
    cli_map = giq.read_exr(tmp_path / "cli" / "flip.exr")["Y"]
    assert flip_map.dtype == np.float32 and flip_map.shape == (24, 32)
    assert np.array_equal(flip_map, cli_map)
    assert mean == cli["metrics"]["flip"]["mean"]["value"]
    _, maps = giq.score(renders["ref"], renders["direct"], maps=True)
    assert np.array_equal(maps["flip"], cli_map)
    assert np.array_equal(maps["abs_error"], giq.read_exr(tmp_path / "cli" / "abs_error.exr")["Y"])
    # LDR-FLIP and another viewing distance are FLIP's own options.
    assert giq.flip(renders["ref"], renders["direct"], hdr=False)[0] != mean
    assert giq.flip(renders["ref"], renders["direct"], ppd=30.0)[0] != mean


def test_ssim_relmse_and_leak_are_the_scores_values(tmp_path, renders):
    run_cli("score", "--ref", renders["ref"], "--test", renders["direct"], "--out", tmp_path / "cli")
    m = read_json(tmp_path / "cli" / "metrics.json")["metrics"]
    ref, test = giq.read_exr(renders["ref"]), giq.read_exr(renders["direct"])
    assert giq.ssim(ref["beauty"], test["beauty"]) == m["ssim"]["value"]
    assert giq.relmse(ref["beauty"], test["beauty"]) == m["relmse"]["value"]
    lk = giq.leak(ref["beauty"], test["beauty"], variance=ref["variance"])
    for key in ("leak", "leak_pixels", "leak_absolute"):
        assert lk["automatic"][key] == m["leak"]["automatic"][key]["value"]
    assert lk["declared"] is None


def test_sequence_metrics_on_arrays_are_giq_scores_on_files(tmp_path):
    # A reference that steps up at frame 4 and a technique that reaches it two frames later,
    # with a flickering error of 2 %.
    rng = np.random.default_rng(5)
    base = rng.random((12, 10, 3), dtype=np.float32) + 0.5
    refs = [base * (1.0 if t < 4 else 2.0) for t in range(10)]
    tests = [base * (1.0 if t < 4 else min(2.0, 1.0 + (t - 3) / 3.0)) * (1.0 + 0.02 * (-1) ** t) for t in range(10)]
    tests = [t.astype(np.float32) for t in tests]
    for t in range(10):
        giq.write_exr(tmp_path / f"ref_{t:04d}.exr", {"beauty": refs[t]})
        giq.write_exr(tmp_path / f"test_{t:04d}.exr", {"beauty": tests[t]})
    run_cli("score", "--ref", tmp_path / "ref_%04d.exr", "--test", tmp_path / "test_%04d.exr", "--frames", "0:9",
            "--out", tmp_path / "cli")
    seq = read_json(tmp_path / "cli" / "metrics.json")["sequence"]
    f = giq.flicker(refs, tests)
    assert f["flicker"] == seq["flicker"]["value"] and f["bias2"] == seq["bias2"]["value"] and f["frames"] == 10
    lag = giq.lag(np.stack(refs), np.stack(tests))  # a (T, H, W, 3) stack is a sequence too
    assert lag["value_frames"] == seq["lag"]["value_frames"] == 2
    assert lag["step_frame"] == 4 and lag["r"] == seq["lag"]["r"]
    assert giq.lag(refs, tests, timings={"frame_gpu_ms": {"median": 2.5}})["lag90_ms"] == 5.0
    # The whole sequence score on arrays is the command line's, less what names the files.
    got = giq.score(refs, tests)
    assert equal_nan(got["sequence"], seq)
    assert equal_nan(got["last_frame"]["metrics"], read_json(tmp_path / "cli" / "metrics.json")["last_frame"]["metrics"])


def test_non_finite_pixels_follow_the_nan_policy(renders):
    ref = giq.read_exr(renders["ref"])["beauty"]
    test = ref.copy()
    test[3, 5, 1] = np.nan
    assert giq.score(ref, test)["metrics"]["nonfinite_pixels"] == 1  # omitted and counted, as giq score does
    with pytest.raises(ValueError, match=r"<test>: pixel \(5, 3\) is NaN; expected finite values"):
        giq.score(ref, test, nan_policy="raise")
    with pytest.raises(ValueError, match="nan_policy: 'drop'; expected 'omit'"):
        giq.relmse(ref, test, nan_policy="drop")


def test_bad_arrays_raise_value_errors_as_the_command_line_words_them(tmp_path, renders):
    ref = giq.read_exr(renders["ref"])["beauty"]
    # A size mismatch on files: the very message giq score prints.
    small = tmp_path / "small.exr"
    giq.write_exr(small, {"beauty": ref[:8, :8]})
    with pytest.raises(ValueError) as e:
        giq.score(renders["ref"], small)
    assert str(e.value) == cli_error("score", "--ref", renders["ref"], "--test", small, "--out", tmp_path / "o")
    # The same check on arrays names them as <reference> and <test>.
    with pytest.raises(ValueError, match=r"^<test>: size: 8x8, expected the reference's 32x24 \(<reference>\)"):
        giq.score(ref, ref[:8, :8])
    with pytest.raises(ValueError, match=r"^<test>: shape \(24, 32, 4\); expected \(H, W, 3\) for RGB or \(H, W\)"):
        giq.score(ref, np.ones((24, 32, 4), np.float32))
    with pytest.raises(ValueError, match=r"^<test>: dtype int32; expected float16, float32 or float64"):
        giq.score(ref, np.ones((24, 32, 3), np.int32))
    with pytest.raises(ValueError, match=r"^<reference>: variance: shape \(24, 32, 2\)"):
        giq.score(ref, ref, variance=np.ones((24, 32, 2), np.float32))
    with pytest.raises(ValueError, match="tonemap: 'filmic'; expected one of none, clamp, reinhard, aces, hable"):
        giq.score(ref, ref, tonemap="filmic")
    with pytest.raises(TypeError, match="unexpected keyword argument 'layers'"):
        giq.score(ref, ref, layers="beauty")
