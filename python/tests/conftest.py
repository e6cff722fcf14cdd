"""Shared fixtures: where the source tree, the built apps and the bundled example are."""

import os
import subprocess

import numpy as np
import pytest

SOURCE_DIR = os.environ.get(
    "COMIC_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
)
BINARY_DIR = os.environ.get("COMIC_BINARY_DIR", os.path.join(SOURCE_DIR, "build"))
EXAMPLE = os.path.join(SOURCE_DIR, "examples", "data", "kitti06_000-011")


def app(name):
    return os.path.join(BINARY_DIR, "bin", name)


def run_app(*args):
    """Runs a built app; returns (exit code, stdout + stderr)."""
    result = subprocess.run(
        [str(a) for a in args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
    )
    return result.returncode, result.stdout


@pytest.fixture
def example():
    return EXAMPLE


def render_square(height=160, width=180, x0=60, y0=70, side=50, inside=200, outside=50):
    """A bright axis-aligned square on a dark background, lightly blurred (a 5-tap binomial);
    its corners lie at the pixel edges (x0 - 0.5, y0 - 0.5) ... with pixel centres at integers."""
    image = np.full((height, width), outside, np.float64)
    image[y0 : y0 + side, x0 : x0 + side] = inside
    kernel = np.array([1, 4, 6, 4, 1], np.float64) / 16.0
    for axis in (0, 1):
        image = np.apply_along_axis(lambda v: np.convolve(v, kernel, mode="same"), axis, image)
    image[:2, :] = image[-2:, :] = outside
    image[:, :2] = image[:, -2:] = outside
    return np.round(image).astype(np.uint8)


def textured_scene(height=200, width=240, seed=3):
    """Random bright and dark rectangles on a mid-grey background: corners everywhere."""
    rng = np.random.default_rng(seed)
    image = np.full((height, width), 110, np.uint8)
    for _ in range(25):
        w, h = rng.integers(15, 50, size=2)
        x, y = rng.integers(5, width - 55), rng.integers(5, height - 55)
        image[y : y + h, x : x + w] = rng.integers(20, 235)
    return image
