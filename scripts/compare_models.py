#!/usr/bin/env python3
"""Compares two camera models of the same frames, e.g. comic_sfm's output with COLMAP's.

Each model is a folder with a COLMAP text `images.txt` (comic_sfm's output folder, or a COLMAP
model converted to text, as scripts/colmap_baseline.sh leaves it). Frames are paired by image name.
The second model is brought onto the first by the similarity (Umeyama) that best maps its camera
centres onto the first's; then the script prints the common frames, the centre RMSE in the
first model's units and as a percentage of its path length, and the mean, median and largest
rotation difference in degrees after the rotations' own best common rotation.

    scripts/compare_models.py REFERENCE_MODEL OTHER_MODEL [--per-frame]
"""

import argparse
import math
import os
import sys

import numpy as np


def quaternion_to_rotation(qw, qx, qy, qz):
    """World-to-camera rotation of a COLMAP images.txt line (Hamilton, w first)."""
    n = math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
    w, x, y, z = qw / n, qx / n, qy / n, qz / n
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def read_images(model_dir):
    """Returns {image name: (R world-to-camera, camera centre)} of a COLMAP text model."""
    path = os.path.join(model_dir, "images.txt")
    cameras = {}
    with open(path) as f:
        lines = [line.rstrip("\n") for line in f if not line.startswith("#")]
    # Each image takes two lines: the pose, then its 2-D points (possibly empty).
    for pose_line in lines[0::2]:
        fields = pose_line.split()
        if len(fields) < 10:
            continue
        qw, qx, qy, qz, tx, ty, tz = (float(v) for v in fields[1:8])
        rotation = quaternion_to_rotation(qw, qx, qy, qz)
        centre = -rotation.T @ np.array([tx, ty, tz])
        cameras[" ".join(fields[9:])] = (rotation, centre)
    return cameras


def umeyama(source, target):
    """Scale s, rotation R, translation t minimising |target - (s R source + t)|^2."""
    mu_s, mu_t = source.mean(axis=0), target.mean(axis=0)
    xs, xt = source - mu_s, target - mu_t
    covariance = xt.T @ xs / len(source)
    u, d, vt = np.linalg.svd(covariance)
    sign = np.eye(3)
    if np.linalg.det(u) * np.linalg.det(vt) < 0:
        sign[2, 2] = -1
    rotation = u @ sign @ vt
    variance = (xs ** 2).sum() / len(source)
    scale = np.trace(np.diag(d) @ sign) / variance
    return scale, rotation, mu_t - scale * rotation @ mu_s


def rotation_angle_deg(rotation):
    # atan2 of sin and cos keeps small angles exact, where acos of the trace loses them.
    skew = rotation - rotation.T
    sine = math.sqrt(skew[2, 1] ** 2 + skew[0, 2] ** 2 + skew[1, 0] ** 2) / 2
    return math.degrees(math.atan2(sine, (np.trace(rotation) - 1) / 2))


def compare(reference, other):
    """Returns a dict of the comparison, or raises ValueError when under 3 frames are common."""
    names = sorted(set(reference) & set(other))
    if len(names) < 3:
        raise ValueError(f"only {len(names)} frames in both models; 3 are needed to align them")
    ref_centres = np.array([reference[n][1] for n in names])
    other_centres = np.array([other[n][1] for n in names])
    scale, rotation, translation = umeyama(other_centres, ref_centres)
    aligned = (scale * (rotation @ other_centres.T)).T + translation
    errors = np.linalg.norm(aligned - ref_centres, axis=1)
    # Centres along a line leave the similarity's rotation about that line free, so the rotations
    # are compared after their own best common rotation G (camera i's world-to-camera rotation in
    # the reference frame is R_other,i G^T ~ R_ref,i, so G^T is the SO(3) projection of the sum of
    # R_other,i^T R_ref,i).
    u, _, vt = np.linalg.svd(sum(other[n][0].T @ reference[n][0] for n in names))
    g_transposed = u @ np.diag([1.0, 1.0, np.linalg.det(u @ vt)]) @ vt
    angles = [rotation_angle_deg(reference[n][0] @ (other[n][0] @ g_transposed).T) for n in names]
    path = float(np.linalg.norm(np.diff(ref_centres, axis=0), axis=1).sum())
    rmse = float(math.sqrt((errors ** 2).mean()))
    return {
        "common": len(names),
        "only_reference": len(set(reference) - set(other)),
        "only_other": len(set(other) - set(reference)),
        "centre_rmse": rmse,
        "centre_rmse_percent_of_path": 100.0 * rmse / path if path > 0 else float("nan"),
        "rotation_mean_deg": float(np.mean(angles)),
        "rotation_median_deg": float(np.median(angles)),
        "rotation_max_deg": float(np.max(angles)),
        "per_frame": list(zip(names, errors.tolist(), angles)),
    }


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reference", help="model folder with images.txt (e.g. COLMAP's)")
    parser.add_argument("other", help="model folder with images.txt (e.g. comic_sfm's output)")
    parser.add_argument("--per-frame", action="store_true", help="print every common frame")
    args = parser.parse_args(argv)
    try:
        result = compare(read_images(args.reference), read_images(args.other))
    except (OSError, ValueError) as error:
        print(f"compare_models.py: {error}", file=sys.stderr)
        return 1
    print(f"common frames {result['common']} (only in reference {result['only_reference']}, "
          f"only in other {result['only_other']}); centre RMSE {result['centre_rmse']:.4g} "
          f"({result['centre_rmse_percent_of_path']:.3g} % of the path); rotation difference "
          f"mean {result['rotation_mean_deg']:.3g} deg, median {result['rotation_median_deg']:.3g}"
          f", max {result['rotation_max_deg']:.3g}")
    if args.per_frame:
        for name, error, angle in result["per_frame"]:
            print(f"{name} {error:.4g} {angle:.3g}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
