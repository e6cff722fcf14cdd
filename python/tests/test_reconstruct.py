"""comic.reconstruct and comic.export_colmap on the bundled KITTI example: the same model, files
and database as the C++ apps, every option and calibration format of the apps, numpy arrays of the
documented dtypes, models read back like pycolmap, progress callbacks, failures reported or raised
with the apps' messages, never crashing."""

import json
import os
import re
import shutil
import sqlite3
import subprocess

import numpy as np
import pytest

import comic
from conftest import EXAMPLE, app, run_app

FRAMES = os.path.join(EXAMPLE, "image_l")
POSES = os.path.join(EXAMPLE, "poses.txt")
CALIB = os.path.join(EXAMPLE, "calib.txt")
MODEL_FILES = [
    "cameras.txt",
    "images.txt",
    "points3D.txt",
    "points.ply",
    "sparse/0/cameras.bin",
    "sparse/0/images.bin",
    "sparse/0/points3D.bin",
]


@pytest.fixture(scope="module")
def harris_run():
    events = []
    reconstruction = comic.reconstruct(FRAMES, detector="harris", gt=POSES, callback=events.append)
    return reconstruction, events


def test_same_model_as_comic_sfm(harris_run, tmp_path):
    reconstruction, _ = harris_run
    code, output = run_app(
        app("comic_sfm"), FRAMES, "--gt", POSES, "--detector", "harris", "--quiet",
        "--output", tmp_path / "app",
    )
    assert code == 0, output
    reconstruction.write(str(tmp_path / "python"))
    for name in MODEL_FILES:
        assert (tmp_path / "python" / name).read_bytes() == (tmp_path / "app" / name).read_bytes(), name
    report = json.loads((tmp_path / "app" / "report.json").read_text())
    for key in ("status", "registered_frames", "points3D", "ground_truth"):
        assert reconstruction.report[key] == report[key], key


def test_arrays_and_their_dtypes(harris_run):
    reconstruction, _ = harris_run
    assert reconstruction.status == "success"
    cameras, images, points = reconstruction.cameras, reconstruction.images, reconstruction.points3D
    assert len(cameras) == 1 and cameras["model"][0] == "PINHOLE"
    # KITTI's calib.txt: fx = 707.0912, cx = 601.8873 (+0.5 in COLMAP's pixel convention).
    assert cameras["params"][0, 0] == 707.0912 and cameras["params"][0, 2] == 601.8873 + 0.5
    assert len(images) == 12 and images["qvec"].shape == (12, 4) and images["tvec"].shape == (12, 3)
    assert np.allclose(np.linalg.norm(images["qvec"], axis=1), 1.0)
    assert list(images["name"]) == ["%06d.png" % i for i in range(12)]
    assert points.dtype["xyz"].shape == (3,) and points["xyz"].dtype == np.float64
    assert points["rgb"].dtype == np.uint8 and points["rgb"].shape == (len(points), 3)
    assert len(points) == reconstruction.report["points3D"]["points"] > 500
    assert np.all(points["track_length"] >= 2)
    obs = reconstruction.points2D
    assert len(obs) == images["num_points2D"].sum()
    matched = obs[obs["point3D_id"] >= 0]
    assert len(matched) == points["track_length"].sum()
    assert set(matched["point3D_id"]) == set(points["point3D_id"].astype(np.int64))
    assert reconstruction.report["ground_truth"]["ate_fraction_of_path"] < 0.01


def test_callback_sees_every_registration(harris_run):
    _, events = harris_run
    assert len(events) == 12
    assert events[-1]["num_registered"] == 12
    assert sorted(e["frame_name"] for e in events) == ["%06d.png" % i for i in range(12)]
    assert events[0]["initial_pair"] and all(e["num_frames"] == 12 for e in events)


def test_loop_closure_keyword(harris_run):
    # KITTI's 12 frames never return: the keyframes are searched, nothing is closed, and the
    # model is the one without loop closure.
    reconstruction, _ = harris_run
    closed = comic.reconstruct(
        FRAMES, detector="harris", gt=POSES, loop_closure=True, loop_closure_max_move=0.2
    )
    assert closed.report["options"]["loop_closure"] is True
    assert closed.report["options"]["loop_closure_max_move"] == 0.2
    assert reconstruction.report["loop_closure"] is None
    assert closed.report["loop_closure"]["keyframes_searched"] >= 3
    assert closed.report["loop_closure"]["loops"] == []
    assert np.array_equal(closed.points3D["xyz"], reconstruction.points3D["xyz"])


def test_write_formats(harris_run, tmp_path):
    reconstruction, _ = harris_run
    reconstruction.write(str(tmp_path / "txt"), model_format="txt", ply_format="ascii")
    assert (tmp_path / "txt" / "cameras.txt").exists()
    assert not (tmp_path / "txt" / "sparse").exists()
    assert (tmp_path / "txt" / "points.ply").read_bytes().startswith(b"ply\nformat ascii 1.0\n")
    with pytest.raises(ValueError, match="--model-format"):
        reconstruction.write(str(tmp_path / "x"), model_format="json")
    with pytest.raises(ValueError, match="PLY format"):
        reconstruction.write(str(tmp_path / "y"), ply_format="binary_big_endian")


def test_failures_are_reported_or_raised(tmp_path):
    one_frame = comic.reconstruct(FRAMES, last=0)
    assert one_frame.status == "too_few_frames"
    assert len(one_frame.images) == 0 and len(one_frame.points3D) == 0
    assert one_frame.failure and "try" in one_frame.failure
    # A failed run writes what comic_sfm writes for it: the report, no model.
    one_frame.write(str(tmp_path / "out"))
    assert (tmp_path / "out" / "report.json").exists()
    assert not (tmp_path / "out" / "cameras.txt").exists()
    assert len(one_frame) == 0
    with pytest.raises(ValueError, match="unknown option 'radius'"):
        comic.reconstruct(FRAMES, radius=20.0)  # comic_sfm's name is search_radius
    with pytest.raises(TypeError, match="max_features"):
        comic.reconstruct(FRAMES, max_features="many")
    with pytest.raises(RuntimeError, match="no such file or folder"):
        comic.reconstruct("/nonexistent/frames")
    with pytest.raises(RuntimeError):
        comic.reconstruct(FRAMES, gt="/nonexistent/poses.txt")


def cli_error(*args):
    """comic_sfm's exit code and its one error line, without the "comic_sfm: error: " prefix."""
    result = subprocess.run(
        [app("comic_sfm"), FRAMES, "--quiet"] + [str(a) for a in args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert result.stderr.startswith("comic_sfm: error: "), result.stderr
    return result.returncode, result.stderr[len("comic_sfm: error: ") :].strip()


@pytest.mark.parametrize(
    "flags, keywords",
    [
        (["--detector", "sift"], {"detector": "sift"}),
        (["--compare", "--detector", "harris"], {"compare": True, "detector": "harris"}),
        (["--detectors", "harris"], {"detectors": "harris"}),
        (["--local-ba-images", "1"], {"local_ba_images": 1}),
        (["--camera-model", "FISHEYE"], {"camera_model": "FISHEYE"}),
        (["--matching", "window:0"], {"matching": "window:0"}),
        (["--prediction", "psychic"], {"prediction": "psychic"}),
        (["--plot-plane", "up"], {"plot_plane": "up"}),
        (["--model-format", "json"], {"model_format": "json"}),
        (["--regions", "a", "--masks", "b"], {"regions": "a", "masks": "b"}),
        (["--overwrite"], {"overwrite": True}),
        (["--threads", "-1"], {"threads": -1}),
        (["--gt-format", "bundler", "--gt", POSES], {"gt_format": "bundler", "gt": POSES}),
        (["--matcher", "sift"], {"matcher": "sift"}),
    ],
)
def test_bad_options_raise_the_command_lines_message(flags, keywords, tmp_path):
    code, message = cli_error(*flags, "--output", tmp_path / "cli")
    assert code == 2, message
    with pytest.raises(ValueError) as raised:
        comic.reconstruct(FRAMES, output=tmp_path / "python", **keywords)
    assert str(raised.value) == message
    assert not (tmp_path / "python").exists() and not (tmp_path / "cli").exists()


def long_options(program):
    help_text = subprocess.run([app(program), "--help"], stdout=subprocess.PIPE, text=True).stdout
    # The option lines of --help: two spaces, an optional short name, the long name.
    names = set(re.findall(r"^  (?:-\w, )?--([a-z0-9-]+)", help_text, re.MULTILINE))
    return {name.replace("-", "_") for name in names} - {"help", "version"}


def test_every_flag_is_a_keyword():
    assert set(comic.RECONSTRUCT_OPTIONS) == long_options("comic_sfm")
    # export_colmap takes the database as its second argument.
    assert set(comic.EXPORT_COLMAP_OPTIONS) | {"colmap_db"} == long_options("comic_export_colmap")


def test_mask_convention_is_the_flags_keyword(tmp_path):
    """--mask-keeps-nonzero is mask_keeps_nonzero=True (COLMAP's convention): with the example
    frames themselves as masks (non-zero nearly everywhere) DAVIS's default drops nearly every
    feature, COLMAP's nearly none."""
    masks = tmp_path / "masks"
    masks.mkdir()
    for name in sorted(os.listdir(FRAMES))[:3]:
        shutil.copy(os.path.join(FRAMES, name), masks / name)
    dropped = comic.reconstruct(FRAMES, last=2, masks=masks)
    kept = comic.reconstruct(FRAMES, last=2, masks=masks, mask_keeps_nonzero=True)
    assert dropped.report["options"]["mask_drops_nonzero"] is True
    assert kept.report["options"]["mask_drops_nonzero"] is False
    assert dropped.report["masked_features"] > 10 * kept.report["masked_features"]
    with pytest.raises(TypeError, match="mask_keeps_nonzero"):
        comic.reconstruct(FRAMES, last=2, masks=masks, mask_keeps_nonzero=1)


def write_calibrations(folder):
    """KITTI 06's camera (fx = fy = 707.0912, cx = 601.8873, cy = 183.1104) in every format
    --intrinsics reads, the ones with distortion with k1 = -0.01."""
    files = {
        "numbers.txt": "707.0912 707.0912 601.8873 183.1104\n",
        "eight.txt": "707.0912 707.0912 601.8873 183.1104 -0.01 0 0 0\n",
        "k.txt": "707.0912 0 601.8873\n0 707.0912 183.1104\n0 0 1\n",
        "opencv.yml": "%YAML:1.0\n---\nimage_width: 1226\nimage_height: 370\n"
        "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
        "   data: [ 707.0912, 0., 601.8873, 0., 707.0912, 183.1104, 0., 0., 1. ]\n"
        "distortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n   dt: d\n"
        "   data: [ -0.01, 0., 0., 0., 0. ]\n",
        "cameras.txt": "# COLMAP\n1 PINHOLE 1226 370 707.0912 707.0912 602.3873 183.6104\n",
    }
    for name, text in files.items():
        (folder / name).write_text(text)
    return files


def test_every_calibration_format_the_command_line_reads(tmp_path):
    files = write_calibrations(tmp_path)
    files["calib.txt"] = None  # KITTI's 3x4 P
    for name in files:
        path = CALIB if name == "calib.txt" else tmp_path / name
        model = comic.reconstruct(FRAMES, intrinsics=path, last=2, detector="fast")
        prior = model.report["camera"]["prior"]
        assert model.report["camera"]["source"] == "file " + str(path), name
        assert prior["params"][0] == pytest.approx(707.0912), name
        assert model.report["options"]["refine_focal"] is False
        assert not model.report["camera"]["refined"], name  # a calibration is held fixed
        distorted = name in ("eight.txt", "opencv.yml")
        assert prior["model"] == ("OPENCV" if distorted else "PINHOLE"), name


def rows(database, table):
    with sqlite3.connect(str(database)) as connection:
        return connection.execute("SELECT * FROM %s ORDER BY 1" % table).fetchall()


def test_reconstruction_reads_models_like_pycolmap(harris_run, tmp_path):
    reconstruction, _ = harris_run
    code, output = run_app(
        app("comic_sfm"), FRAMES, "--gt", POSES, "--quiet", "--output", tmp_path / "app",
        "--model-format", "bin",
    )
    assert code == 0, output
    # comic_sfm's output folder: the binary model in sparse/0/, and report.json beside it.
    read = comic.Reconstruction(tmp_path / "app")
    assert read.status == "success" and read.report["status"] == "success"
    assert read.path == str(tmp_path / "app")
    for name in ("cameras", "images", "points3D", "points2D"):
        assert np.array_equal(getattr(read, name), getattr(reconstruction, name)), name
    # A text model, as COLMAP's model_converter writes it, without a report.
    reconstruction.write_text(tmp_path / "text")
    text = comic.Reconstruction(tmp_path / "text")
    assert text.status is None and text.report == {}
    assert np.array_equal(text.points3D, reconstruction.points3D)
    with pytest.raises(RuntimeError, match="no COLMAP model"):
        comic.Reconstruction(tmp_path)
    with pytest.raises(RuntimeError, match="no such file or folder"):
        comic.Reconstruction(tmp_path / "missing")


def test_export_colmap_writes_the_apps_database(tmp_path):
    code, output = run_app(
        app("comic_export_colmap"), FRAMES, "--colmap-db", tmp_path / "app.db", "--intrinsics", CALIB,
        "--last", "5",
    )
    assert code == 0, output
    summary = comic.export_colmap(FRAMES, str(tmp_path / "python.db"), intrinsics=CALIB, last=5)
    assert summary["num_images"] == 6 and summary["known_intrinsics"]
    assert summary["num_verified_pairs"] > 0
    assert "colmap mapper" in summary["mapper_command"]
    assert summary["matching"] == "sequential"
    for table in ("cameras", "images", "keypoints", "matches", "two_view_geometries"):
        assert rows(tmp_path / "python.db", table) == rows(tmp_path / "app.db", table), table
    with pytest.raises(RuntimeError, match="python.db"):
        comic.export_colmap(FRAMES, str(tmp_path / "python.db"), intrinsics=CALIB, last=5)
    with pytest.raises(ValueError):
        comic.export_colmap(FRAMES, str(tmp_path / "w.db"), window=0)
