"""comic.reconstruct and comic.export_colmap on the bundled KITTI example: the same model, files
and database as the C++ apps, numpy arrays of the documented dtypes, progress callbacks, failures
reported or raised, never crashing."""

import json
import os
import sqlite3

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


def test_write_formats(harris_run, tmp_path):
    reconstruction, _ = harris_run
    reconstruction.write(str(tmp_path / "txt"), model_format="txt", ply_format="ascii")
    assert (tmp_path / "txt" / "cameras.txt").exists()
    assert not (tmp_path / "txt" / "sparse").exists()
    assert (tmp_path / "txt" / "points.ply").read_bytes().startswith(b"ply\nformat ascii 1.0\n")
    with pytest.raises(ValueError, match="model_format"):
        reconstruction.write(str(tmp_path / "x"), model_format="json")
    with pytest.raises(ValueError, match="PLY format"):
        reconstruction.write(str(tmp_path / "y"), ply_format="binary_big_endian")


def test_failures_are_reported_or_raised(tmp_path):
    one_frame = comic.reconstruct(FRAMES, last=0)
    assert one_frame.status == "too_few_frames"
    assert len(one_frame.images) == 0 and len(one_frame.points3D) == 0
    with pytest.raises(RuntimeError, match="nothing to write"):
        one_frame.write(str(tmp_path / "out"))
    with pytest.raises(ValueError, match="unknown detector"):
        comic.reconstruct(FRAMES, detector="sift")
    with pytest.raises(ValueError, match="unknown option 'radius'"):
        comic.reconstruct(FRAMES, radius=20.0)  # comic_sfm's name is search_radius
    with pytest.raises(ValueError):
        comic.reconstruct(FRAMES, local_ba_images=1)
    with pytest.raises(RuntimeError, match="no such file or folder"):
        comic.reconstruct("/nonexistent/frames")
    with pytest.raises(RuntimeError):
        comic.reconstruct(FRAMES, gt="/nonexistent/poses.txt")


def rows(database, table):
    with sqlite3.connect(str(database)) as connection:
        return connection.execute("SELECT * FROM %s ORDER BY 1" % table).fetchall()


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
    for table in ("cameras", "images", "keypoints", "matches", "two_view_geometries"):
        assert rows(tmp_path / "python.db", table) == rows(tmp_path / "app.db", table), table
    with pytest.raises(RuntimeError, match="python.db"):
        comic.export_colmap(FRAMES, str(tmp_path / "python.db"), intrinsics=CALIB, last=5)
    with pytest.raises(ValueError):
        comic.export_colmap(FRAMES, str(tmp_path / "w.db"), window=0)
