#!/usr/bin/env python3
"""How far each model turns its cameras from its first frame: a check without ground truth.

A clip filmed along one straight street (VOT car1) or down one corridor should end looking
where it started; a model whose cameras turn tens of degrees over it has drifted, whatever its
reprojection error. For each model (a folder with a COLMAP text images.txt), the rotation angle
of every K-th frame (the frames all models share, by image name) from the first shared frame,
and the largest.

    scripts/model_turn.py MODEL [MODEL ...] [--every K]
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_models import read_images, rotation_angle_deg  # noqa: E402


def turns_from_first(models):
    """(shared image names in order, per model the angle of each from the first, degrees).

    models: {image name: (world-to-camera R, centre)} each, as compare_models.read_images gives.
    Raises ValueError when fewer than 2 frames are in every model.
    """
    names = sorted(set.intersection(*(set(m) for m in models)))
    if len(names) < 2:
        raise ValueError(f"only {len(names)} frames in every model; 2 are needed")
    first = names[0]
    return names, [[rotation_angle_deg(m[n][0] @ m[first][0].T) for n in names] for m in models]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("models", nargs="+", help="folders with a COLMAP text images.txt")
    parser.add_argument("--every", type=int, default=20, help="print every K-th shared frame")
    args = parser.parse_args()
    if args.every < 1:
        parser.error("--every must be at least 1")
    models = []
    for folder in args.models:
        try:
            models.append(read_images(folder))
        except OSError as error:
            sys.exit(f"model_turn.py: {folder}: {error.strerror}")
    try:
        names, turns = turns_from_first(models)
    except ValueError as error:
        sys.exit(f"model_turn.py: {error}")
    for number, folder in enumerate(args.models, 1):
        print(f"model {number}: {folder}")
    print("frame        " + " ".join(f"{'model ' + str(n):>10}" for n in range(1, len(models) + 1)))
    shown = list(range(0, len(names), args.every))
    if shown[-1] != len(names) - 1:
        shown.append(len(names) - 1)
    for i in shown:
        print(f"{names[i]} " + " ".join(f"{t[i]:10.1f}" for t in turns))
    print("largest " + " ".join(f"{max(t):10.1f}" for t in turns))
    print(f"({len(names)} frames shared, degrees from {names[0]})")


if __name__ == "__main__":
    main()
