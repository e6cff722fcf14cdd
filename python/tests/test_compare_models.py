"""scripts/compare_models.py on models with known answers: a model against a similar copy of
itself, and against a copy with one camera turned by a known angle."""

import math
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
import compare_models  # noqa: E402


def rotation_about(axis, degrees):
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    a = math.radians(degrees)
    return np.eye(3) + math.sin(a) * k + (1 - math.cos(a)) * k @ k


def quaternion(rotation):
    w = math.sqrt(max(0.0, 1 + np.trace(rotation))) / 2
    return (w, (rotation[2, 1] - rotation[1, 2]) / (4 * w),
            (rotation[0, 2] - rotation[2, 0]) / (4 * w), (rotation[1, 0] - rotation[0, 1]) / (4 * w))


def write_model(folder, cameras):
    """cameras: list of (name, world-to-camera R, centre)."""
    os.makedirs(folder)
    with open(os.path.join(folder, "images.txt"), "w") as f:
        f.write("# IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n")
        for i, (name, rotation, centre) in enumerate(cameras):
            t = -rotation @ centre
            q = quaternion(rotation)
            f.write(f"{i + 1} {q[0]!r} {q[1]!r} {q[2]!r} {q[3]!r} {t[0]!r} {t[1]!r} {t[2]!r} 1 "
                    f"{name}\n\n")


def orbit(count):
    cameras = []
    for i in range(count):
        rotation = rotation_about([0, 1, 0], 10 * i) @ rotation_about([1, 0, 0], 3 * i)
        cameras.append((f"{i:04d}.png", rotation, np.array([math.cos(i / 3), 0.1 * i, 2.0])))
    return cameras


def similar_copy(cameras, scale, rotation, translation):
    """The same cameras in a world x' = scale rotation x + translation."""
    return [(name, r @ rotation.T, scale * rotation @ c + translation) for name, r, c in cameras]


def test_a_similar_copy_agrees_exactly(tmp_path):
    cameras = orbit(8)
    write_model(tmp_path / "a", cameras)
    write_model(tmp_path / "b",
                similar_copy(cameras, 3.5, rotation_about([1, 2, 3], 70), np.array([5, -2, 1])))
    result = compare_models.compare(compare_models.read_images(tmp_path / "a"),
                                    compare_models.read_images(tmp_path / "b"))
    assert result["common"] == 8
    assert result["centre_rmse"] < 1e-9
    assert result["rotation_max_deg"] < 1e-6


def test_one_turned_camera_is_found(tmp_path):
    cameras = orbit(12)
    turned = list(cameras)
    name, rotation, centre = turned[5]
    turned[5] = (name, rotation_about([0, 0, 1], 4.0) @ rotation, centre)
    write_model(tmp_path / "a", cameras)
    write_model(tmp_path / "b", turned)
    result = compare_models.compare(compare_models.read_images(tmp_path / "a"),
                                    compare_models.read_images(tmp_path / "b"))
    assert result["centre_rmse"] < 1e-9
    # The common rotation moves by about 4/12 degrees; the turned camera keeps most of its 4.
    assert 3.3 < result["rotation_max_deg"] < 4.0
    assert result["rotation_median_deg"] < 0.5


def test_frames_are_paired_by_name_and_too_few_are_refused(tmp_path):
    cameras = orbit(6)
    write_model(tmp_path / "a", cameras)
    write_model(tmp_path / "b", cameras[4:] + [("other.png", np.eye(3), np.zeros(3))])
    with pytest.raises(ValueError, match="only 2 frames"):
        compare_models.compare(compare_models.read_images(tmp_path / "a"),
                               compare_models.read_images(tmp_path / "b"))
