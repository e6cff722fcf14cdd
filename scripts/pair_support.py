#!/usr/bin/env python3
"""Which of several models of the same frames do a COLMAP database's verified pairs support?

Without ground truth, two models that disagree (scripts/compare_models.py) can still be judged by
evidence neither was fitted to: the two-view geometries of another matcher. For every pair the
database verified (at least 30 inlier matches), this prints, per model, the median Sampson
distance in pixels of the pair's inlier matches to the epipolar geometry the model's cameras imply
(its own SIMPLE_RADIAL intrinsics undone first), then over the pairs: the median, the 90th
percentile and the share of pairs over 2 px. Only pairs whose frames every model registers count.

    scripts/pair_support.py DATABASE.db MODEL_DIR [MODEL_DIR ...]

e.g. COLMAP's database from scripts/colmap_baseline.sh against COLMAP's model and comic_sfm's.
"""
import os
import sqlite3
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare_models as c  # noqa: E402

COLMAP_PAIR_ID_FACTOR = 2147483647
MIN_PAIR_INLIERS = 30
# TwoViewGeometry configurations with a verified geometry: calibrated, uncalibrated, planar,
# planar or panoramic.
VERIFIED_CONFIGS = (2, 3, 4, 6)


def read_camera(model):
    """f, cx, cy, k of the model's first camera (SIMPLE_RADIAL's parameters)."""
    with open(os.path.join(model, "cameras.txt")) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            fields = line.split()
            return tuple(float(v) for v in fields[4:8])
    raise ValueError(f"{model}: no camera in cameras.txt")


def normalised(points, f, cx, cy, k):
    """Pixel points (COLMAP's +0.5 convention on both) to undistorted normalised coordinates."""
    x = (points - [cx, cy]) / f
    u = x.copy()
    for _ in range(10):  # fixed-point inversion of x = u (1 + k |u|^2)
        u = x / (1 + k * (u ** 2).sum(1, keepdims=True))
    return u


def median_sampson_px(essential, x1, x2, f):
    h1 = np.c_[x1, np.ones(len(x1))]
    h2 = np.c_[x2, np.ones(len(x2))]
    line2 = h1 @ essential.T
    line1 = h2 @ essential
    residual = (h2 * line2).sum(1)
    denominator = np.sqrt((line2[:, :2] ** 2).sum(1) + (line1[:, :2] ** 2).sum(1))
    return float(np.median(np.abs(residual) / denominator)) * f


def model_essential(images, name1, name2):
    """The essential matrix of two registered images of a model, or None without a baseline."""
    rotation1, centre1 = images[name1]
    rotation2, centre2 = images[name2]
    translation = rotation2 @ (centre1 - centre2)
    norm = np.linalg.norm(translation)
    if norm == 0:
        return None
    t = translation / norm
    cross = np.array([[0, -t[2], t[1]], [t[2], 0, -t[0]], [-t[1], t[0], 0]])
    return cross @ rotation2 @ rotation1.T


def main(argv):
    if len(argv) < 2:
        print(__doc__.strip().splitlines()[-3].strip(), file=sys.stderr)
        return 2
    database, models = argv[0], argv[1:]
    db = sqlite3.connect(database)
    names = dict(db.execute("select image_id, name from images"))
    keypoints = {}
    for image_id, rows, cols, data in db.execute("select image_id, rows, cols, data from keypoints"):
        keypoints[image_id] = np.frombuffer(data, dtype=np.float32).reshape(rows, cols)[:, :2]
    loaded = [(m, c.read_images(m), read_camera(m)) for m in models]
    # Each image's keypoints undistorted once per model (COLMAP puts a pixel's centre at +0.5;
    # the models' principal points, written by COLMAP's convention, too).
    normalised_keypoints = [{} for _ in loaded]
    results = {m: [] for m in models}
    for pair_id, rows, data, config in db.execute(
            "select pair_id, rows, data, config from two_view_geometries"):
        if rows < MIN_PAIR_INLIERS or config not in VERIFIED_CONFIGS:
            continue
        image2 = pair_id % COLMAP_PAIR_ID_FACTOR
        image1 = (pair_id - image2) // COLMAP_PAIR_ID_FACTOR
        name1, name2 = names[image1], names[image2]
        if not all(name1 in images and name2 in images for _, images, _ in loaded):
            continue
        matches = np.frombuffer(data, dtype=np.uint32).reshape(rows, 2)
        for (model, images, (f, cx, cy, k)), cache in zip(loaded, normalised_keypoints):
            essential = model_essential(images, name1, name2)
            if essential is None:
                continue
            for image_id in (image1, image2):
                if image_id not in cache:
                    cache[image_id] = normalised(keypoints[image_id], f, cx, cy, k)
            results[model].append(median_sampson_px(
                essential, cache[image1][matches[:, 0]], cache[image2][matches[:, 1]], f))
    for model in models:
        a = np.array(results[model])
        print(f"{model}: {len(a)} pairs, median of pair medians {np.median(a):.3f} px, "
              f"p90 {np.percentile(a, 90):.3f}, pairs over 2 px {np.mean(a > 2) * 100:.1f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
