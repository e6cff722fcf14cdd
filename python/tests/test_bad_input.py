"""Issue 29 in Python: the apps' checks, every C++ error a Python exception with the apps' text,
never an abort of the interpreter, and messages that neither dump the image nor name internals."""

import os
import struct
import subprocess
import sys

import numpy as np
import pytest

import comic
from conftest import EXAMPLE, textured_scene

CORES = os.cpu_count() or 1


def png_header(width, height):
    """A PNG's signature and IHDR declaring width x height (8-bit grey), then 1000 zero bytes."""
    ihdr = struct.pack(">II5B", width, height, 8, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + struct.pack(">I", 13) + b"IHDR" + ihdr + b"\0" * 1004


def test_huge_thread_counts_raise_instead_of_aborting():
    # threads=10**6 took the interpreter down with SIGABRT; run it in a child so that a regression
    # is a failed test, not a lost test session.
    code = (
        "import numpy as np, comic\n"
        "try:\n"
        "    comic.detect(np.zeros((64, 64), np.uint8), threads=10**6)\n"
        "except ValueError as e:\n"
        "    print(e)\n"
    )
    env = dict(os.environ)
    child = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120
    )
    assert child.returncode == 0, child.stderr
    assert "--threads must be >= 0 and <= %d" % CORES in child.stdout


@pytest.mark.parametrize(
    "call",
    [
        lambda: comic.detect(textured_scene(), threads=CORES + 1),
        lambda: comic.detect(textured_scene(), detector="comic-paper", threads=CORES + 64),
        lambda: comic.track([textured_scene()] * 2, detector_options={"threads": CORES + 1}),
        lambda: comic.reconstruct(EXAMPLE + "/image_l", threads=CORES + 1),
        lambda: comic.export_colmap(EXAMPLE + "/image_l", "/tmp/never.db", threads=-1),
    ],
)
def test_thread_counts_are_capped_at_the_cores_as_in_the_apps(call):
    with pytest.raises(ValueError, match="threads must be >= 0 and <= %d \\(the hardware" % CORES):
        call()


@pytest.mark.parametrize(
    "call, named",
    [
        (lambda: comic.detect(textured_scene(), threads=10**20), "option 'threads' = 10"),
        (lambda: comic.detect(textured_scene(), max_pixels=10**30), "option 'max_pixels' = 10"),
        (lambda: comic.imread(EXAMPLE + "/image_l/000000.png", resize_height=10**12), "resize_h"),
        (lambda: comic.track([textured_scene()] * 2, max_pixels=-(10**40)), "'max_pixels' = -1"),
    ],
)
def test_integers_beyond_any_range_are_bad_values_not_wrong_types(call, named):
    # threads=10**20 was "option 'threads' has the wrong type (<class 'int'>)".
    with pytest.raises(ValueError, match="is beyond the range of a (32|64)-bit integer") as info:
        call()
    assert named in str(info.value)


def test_the_pixel_budget_holds_for_arrays_files_and_sequences(tmp_path):
    image = np.zeros((100, 120), np.uint8)
    with pytest.raises(RuntimeError, match="120x100 = 12000 pixels exceeds the budget of 5000"):
        comic.detect(image, max_pixels=5000)
    assert len(comic.detect(image, max_pixels=12000)[0]) == 0
    with pytest.raises(RuntimeError, match="track: frame 0: 120x100"):
        comic.track([image, image], max_pixels=5000)
    with pytest.raises(RuntimeError, match="000000.png: 1226x370"):
        comic.track(EXAMPLE + "/image_l", max_pixels=1000)
    with pytest.raises(RuntimeError, match="1226x370"):
        comic.reconstruct(EXAMPLE + "/image_l", max_pixels=1000)
    with pytest.raises(ValueError, match="--max-pixels must be in \\[1, "):
        comic.detect(image, max_pixels=0)
    # A small file declaring 30000 x 30000 is refused from its header, not decoded (900 MB).
    huge = tmp_path / "huge.png"
    huge.write_bytes(png_header(30000, 30000))
    with pytest.raises(RuntimeError, match="huge.png: 30000x30000 = 900000000 pixels exceeds"):
        comic.imread(huge)
    assert comic.imread(EXAMPLE + "/image_l/000000.png", max_pixels=1226 * 370).shape == (370, 1226)


def test_resize_height_has_the_apps_range():
    expected = "--resize-height must be 0 \\(original size\\) or in \\[8, 16384\\]"
    with pytest.raises(ValueError, match=expected):
        comic.imread(EXAMPLE + "/image_l/000000.png", resize_height=1)
    with pytest.raises(ValueError, match="--resize-height must be 0"):
        comic.track(EXAMPLE + "/image_l", resize_height=3)


def test_wrong_types_are_one_short_line_without_the_image():
    image = np.full((300, 300), 77, np.uint8)
    for call in (
        lambda: comic.detect(image, detector=None),
        lambda: comic.detect(image, detector=3),
        lambda: comic.track([image, image], detector=None),
    ):
        with pytest.raises(TypeError) as info:
            call()
        message = str(info.value)
        assert "must be a str (one of comic, comic-paper, harris" in message
        assert "array(" not in message and "77" not in message
    features, masks = comic.detect(textured_scene())
    with pytest.raises(TypeError) as info:
        comic.match(textured_scene(), features, textured_scene(), features, masks, masks, cost=5)
    assert "option 'cost' has the wrong type" in str(info.value)
    assert "array(" not in str(info.value) and len(str(info.value)) < 300
    with pytest.raises(TypeError) as info:
        comic.reconstruct(EXAMPLE + "/image_l", detector_options=7)
    assert "array(" not in str(info.value) and len(str(info.value)) < 300


def test_unknown_detectors_are_listed_not_pointed_at():
    with pytest.raises(ValueError) as info:
        comic.detect(np.zeros((20, 20), np.uint8), detector="sift")
    message = str(info.value)
    assert "unknown detector 'sift' (valid: comic, comic-paper, harris, hessian, mser, fast" in (
        message
    )
    assert "detector_names" not in message


def test_calibration_values_are_range_checked_naming_the_file(tmp_path):
    calib = tmp_path / "calib_cx.txt"
    calib.write_text("700 0 1e300\n0 700 185\n0 0 1\n")
    with pytest.raises(RuntimeError, match="calib_cx.txt: principal point cx = 1e\\+300"):
        comic.reconstruct(EXAMPLE + "/image_l", intrinsics=str(calib), last=2)
    with pytest.raises(RuntimeError, match="calib_cx.txt: principal point cx"):
        comic.export_colmap(EXAMPLE + "/image_l", str(tmp_path / "a.db"), intrinsics=str(calib))
    assert not (tmp_path / "a.db").exists()


def test_export_never_writes_over_its_inputs(tmp_path):
    frames = tmp_path / "frames"
    frames.mkdir()
    for name in ("000000.png", "000001.png"):
        (frames / name).write_bytes(open(EXAMPLE + "/image_l/" + name, "rb").read())
    before = (frames / "000000.png").read_bytes()
    with pytest.raises(ValueError, match="--colmap-db lies inside the input FRAMES folder"):
        comic.export_colmap(str(frames), str(frames / "000000.png"), overwrite=True)
    assert (frames / "000000.png").read_bytes() == before


def test_reconstruct_never_writes_over_its_inputs(tmp_path):
    # A COLMAP project as the output: its calibration and model are inputs at paths a run writes.
    (tmp_path / "sparse" / "0").mkdir(parents=True)
    (tmp_path / "sparse" / "0" / "cameras.txt").write_text("# ground truth\n")
    calib = tmp_path / "cameras.txt"
    calib.write_text("# calibration\n1 PINHOLE 1226 370 700 700 613 185\n")
    before = calib.read_bytes()
    with pytest.raises(ValueError, match="the input --intrinsics would be replaced"):
        comic.reconstruct(EXAMPLE + "/image_l", intrinsics=str(calib), output=str(tmp_path))
    with pytest.raises(ValueError, match="the input --gt would be replaced"):
        comic.reconstruct(EXAMPLE + "/image_l", gt=str(tmp_path / "sparse" / "0"),
                          output=str(tmp_path))
    assert calib.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cameras.txt", "sparse"]


def test_imread_of_none_is_a_type_error():
    with pytest.raises(TypeError, match="imread: path must be a str or os.PathLike, got NoneType"):
        comic.imread(None)


def test_messages_are_one_printable_line():
    with pytest.raises(RuntimeError) as info:
        comic.imread("/nonexistent/stra\u00dfe\n.png")
    message = str(info.value)
    assert "\n" not in message and "stra\u00dfe" in message


def test_frame_names_no_model_can_hold_are_refused_before_any_work(tmp_path):
    for k in range(2):
        name = "img %06d.png" % k
        (tmp_path / name).write_bytes(open(EXAMPLE + "/image_l/%06d.png" % k, "rb").read())
    expected = "frame name 'img 000000.png' is empty or holds whitespace"
    with pytest.raises(RuntimeError, match=expected):
        comic.reconstruct(str(tmp_path))
