"""giq.read_exr and giq.write_exr: round trips, float16, metadata, and the errors of bad input."""

import os

import numpy as np
import pytest

import giq
from conftest import cli_error


def test_round_trip_keeps_every_layer_channel_and_header_string(tmp_path):
    rng = np.random.default_rng(1)
    layers = {"beauty": rng.random((5, 7, 3), dtype=np.float32) * 1e6,
              "indirect": rng.random((5, 7, 3), dtype=np.float32),
              "objectId": np.arange(35, dtype=np.float32).reshape(5, 7)}
    path = tmp_path / "a.exr"
    giq.write_exr(path, layers, {"giq.note": "hello", "owner": "test"})
    back = giq.read_exr(path)
    assert sorted(back) == ["beauty", "indirect", "objectId"]
    for name, a in layers.items():
        assert back[name].dtype == np.float32 and back[name].shape == a.shape
        assert np.array_equal(back[name], a), name  # float32 is stored as float32: bit for bit
    assert back.metadata["giq.note"] == "hello" and back.metadata["owner"] == "test"
    assert back.channels["indirect"] == ["indirect.R", "indirect.G", "indirect.B"]


def test_a_layers_object_keeps_its_channel_names_through_a_round_trip(tmp_path, renders):
    ref = giq.read_exr(renders["ref"])
    assert ref.channels["N"] == ["N.X", "N.Y", "N.Z"]  # the reference's normals are a vector layer
    giq.write_exr(tmp_path / "copy.exr", ref, ref.metadata)
    copy = giq.read_exr(tmp_path / "copy.exr")
    assert copy.channels == ref.channels and copy.metadata == ref.metadata
    for name in ref:
        assert np.array_equal(copy[name], ref[name], equal_nan=True), name


def test_float16_arrays_are_stored_as_half(tmp_path):
    rng = np.random.default_rng(2)
    a32 = rng.random((64, 64, 3), dtype=np.float32)
    a16 = a32.astype(np.float16)
    giq.write_exr(tmp_path / "f32.exr", {"beauty": a32})
    giq.write_exr(tmp_path / "f16.exr", {"beauty": a16})
    assert np.array_equal(giq.read_exr(tmp_path / "f16.exr")["beauty"], a16.astype(np.float32))
    # Half is 2 bytes a value against 4: random data does not compress, so the file is near half the size.
    assert os.path.getsize(tmp_path / "f16.exr") < 0.7 * os.path.getsize(tmp_path / "f32.exr")


def test_any_memory_order_and_float_width_reads_the_same(tmp_path):
    rng = np.random.default_rng(3)
    a = rng.random((6, 9, 3)).astype(np.float16).astype(np.float32)  # values exact in every width
    for variant in (np.asfortranarray(a), a.astype(np.float64), a.astype(np.float16), a[:, ::-1, :][:, ::-1, :]):
        giq.write_exr(tmp_path / "v.exr", {"beauty": variant})
        assert np.array_equal(giq.read_exr(tmp_path / "v.exr")["beauty"], a)


def test_a_bad_write_raises_and_leaves_the_previous_file(tmp_path):
    path = tmp_path / "keep.exr"
    giq.write_exr(path, {"beauty": np.ones((4, 4, 3), np.float32)})
    before = path.read_bytes()
    with pytest.raises(ValueError, match=r"shape \(4, 4, 4\); expected \(H, W, 3\) for RGB or \(H, W\) for grey"):
        giq.write_exr(path, {"beauty": np.ones((4, 4, 4), np.float32)})
    with pytest.raises(ValueError, match=r"is 5x4, expected 4x4"):
        giq.write_exr(path, {"beauty": np.ones((4, 4, 3), np.float32), "Z": np.ones((4, 5), np.float32)})
    with pytest.raises(ValueError, match="dtype int64; expected float16, float32 or float64"):
        giq.write_exr(path, {"beauty": np.ones((4, 4, 3), np.int64)})
    with pytest.raises(ValueError, match="a list; expected a numpy array of floats"):
        giq.write_exr(path, {"beauty": [[1.0]]})
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["keep.exr"]  # no temporary file left behind


def test_reading_a_missing_or_foreign_file_raises_what_the_command_line_prints(tmp_path):
    missing = tmp_path / "missing.exr"
    with pytest.raises(ValueError) as e:
        giq.read_exr(missing)
    assert str(e.value) == cli_error("score", "--ref", missing, "--test", missing, "--out", tmp_path / "o")
    (tmp_path / "text.exr").write_text("not an image")
    with pytest.raises(ValueError, match="not an OpenEXR file"):
        giq.read_exr(tmp_path / "text.exr")
