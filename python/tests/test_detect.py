"""comic.detect: dtypes and shapes, known answers on synthetic images, equality with comic_detect
on a bundled frame, bad input raising."""

import json
import os

import numpy as np
import pytest

import comic
from conftest import EXAMPLE, SOURCE_DIR, app, render_square, run_app, textured_scene


def test_version_is_the_project_version():
    with open(os.path.join(SOURCE_DIR, "CMakeLists.txt")) as f:
        text = f.read()
    assert "project(comic_sfm VERSION %s " % comic.__version__ in text
    assert comic.DETECTORS == ("comic", "comic-paper", "harris", "hessian", "mser", "fast")


def test_detect_returns_structured_features_and_side_masks():
    features, masks = comic.detect(textured_scene(), detector="comic")
    assert features.dtype == comic.FEATURE_DTYPE
    assert features.dtype.names == (
        "x", "y", "scale", "response", "cornerness", "level", "polarity",
    )
    assert len(features) > 30
    assert masks.dtype == np.uint8 and masks.shape == (len(features), 23, 23)
    assert set(np.unique(masks)) <= {0, 1, 2}
    # Strongest first; CoMIC's polarity is never 0 and every CoMIC feature has a side mask, nearly
    # always with pixels on both sides (a corner's patch can lie almost wholly on one side).
    assert np.all(np.diff(features["response"]) <= 0)
    assert set(np.unique(features["polarity"])) <= {-1, 1}
    assert np.all((masks != 0).any(axis=(1, 2)))
    assert np.mean((masks == 1).any(axis=(1, 2)) & (masks == 2).any(axis=(1, 2))) > 0.9
    assert np.all(features["scale"] == np.float32(8.4))


def test_the_squares_four_corners_are_found():
    features, _ = comic.detect(render_square())
    for corner in [(59.5, 69.5), (109.5, 69.5), (59.5, 119.5), (109.5, 119.5)]:
        distance = np.hypot(features["x"] - corner[0], features["y"] - corner[1])
        assert distance.min() < 1.5, corner
    # The corners point into the bright square.
    nearest = np.argmin(np.hypot(features["x"] - 59.5, features["y"] - 69.5))
    assert features["polarity"][nearest] == 1


def test_baselines_and_their_options():
    image = textured_scene()
    for name in comic.DETECTORS:
        features, masks = comic.detect(image, detector=name)
        assert len(features) >= 5, name
        assert masks.shape == (len(features), 23, 23)
        if not name.startswith("comic"):
            # No iso level, cornerness or side masks outside the two CoMIC searches (MSER has a
            # polarity).
            assert np.all(features["level"] == -1) and np.all(masks == 0), name
            assert np.all(features["cornerness"] == 0), name
    wide, _ = comic.detect(image, detector="harris", integration_sigma=4.0)
    narrow, _ = comic.detect(image, detector="harris", integration_sigma=1.5)
    assert len(wide) != len(narrow)
    # A BGR image gives the same features as its grey version.
    bgr = np.repeat(image[:, :, None], 3, axis=2)
    grey_features, _ = comic.detect(image, detector="fast")
    bgr_features, _ = comic.detect(bgr, detector="fast")
    assert np.array_equal(grey_features, bgr_features)


def test_threads_do_not_change_the_result():
    image = textured_scene(seed=9)
    one, masks_one = comic.detect(image, threads=1)
    two, masks_two = comic.detect(image, threads=2)
    assert np.array_equal(one, two) and np.array_equal(masks_one, masks_two)


def test_equal_to_comic_detect_on_a_bundled_frame(tmp_path):
    path = os.path.join(EXAMPLE, "image_l", "000000.png")
    out = tmp_path / "features.json"
    code, output = run_app(app("comic_detect"), path, "--json", out)
    assert code == 0, output
    expected = json.loads(out.read_text())["features"]
    features, masks = comic.detect(comic.imread(path))
    assert len(features) == len(expected) > 100
    for got, mask, want in zip(features, masks, expected):
        for name in ("x", "y", "scale", "response", "cornerness"):
            assert got[name] == np.float32(want[name]), name
        assert got["level"] == want["level"]
        assert got["polarity"] == {"bright": 1, "dark": -1, "none": 0}[want["polarity"]]
        rows = ["".join("+-."[{1: 0, 2: 1, 0: 2}[v]] for v in row) for row in mask]
        assert rows == want["side_mask"]


# Both doors on the same pixels with the same options, each spelt as its door spells it: the
# flags and keywords come from one table (sfm/run/detector_option_table.h), so they must agree to
# the bit. Small and capped so that each case costs well under a second.
DOORS = [
    ("comic", [], {}),
    (
        "comic",
        ["--scale", "6", "--presmoothing-sigma", "1", "--bridge-levels", "20", "--max-features",
         "150"],
        dict(scale=6.0, presmoothing_sigma=1.0, bridge_levels=20, max_features=150),
    ),
    (
        "comic-paper",
        ["--full-resolution-init", "--every-path", "--min-cornerness", "0.05", "--max-features",
         "120"],
        dict(full_resolution_init=True, every_path=True, min_cornerness=0.05, max_features=120),
    ),
]


@pytest.mark.parametrize("detector, flags, keywords", DOORS, ids=["comic", "comic-options",
                                                                  "paper-options"])
def test_both_doors_give_the_same_features(tmp_path, detector, flags, keywords):
    path = os.path.join(EXAMPLE, "image_l", "000000.png")
    out = tmp_path / "features.json"
    code, output = run_app(
        app("comic_detect"), path, "--resize-height", "188", "--detector", detector, "--json",
        out, *flags
    )
    assert code == 0, output
    expected = json.loads(out.read_text())["features"]
    features, _ = comic.detect(comic.imread(path, resize_height=188), detector, **keywords)
    assert len(features) == len(expected) > 20
    if "max_features" in keywords:
        assert len(features) == keywords["max_features"]
    for name in ("x", "y", "scale"):
        assert np.array_equal(features[name], np.array([f[name] for f in expected], np.float32))


def test_the_old_keywords_still_work():
    image = textured_scene(seed=3)
    new, _ = comic.detect(image, "comic-paper", full_resolution_init=True, no_neighbour_seeds=True)
    old, _ = comic.detect(
        image, "comic-paper", coarse_initialisation=False, seed_neighbouring_corners=False
    )
    assert np.array_equal(new, old)


@pytest.mark.parametrize(
    "call, error",
    [
        (lambda: comic.detect(np.zeros((50, 50), np.float32)), ValueError),
        (lambda: comic.detect(np.zeros((50, 50, 4), np.uint8)), ValueError),
        (lambda: comic.detect(np.zeros((0, 50), np.uint8)), ValueError),
        (lambda: comic.detect(np.zeros((50, 50), np.uint8), detector="sift"), ValueError),
        (lambda: comic.detect(np.zeros((50, 50), np.uint8), scale=-1.0), ValueError),
        (lambda: comic.detect(np.zeros((50, 50), np.uint8), sigma=2.0), ValueError),
        (lambda: comic.detect(np.zeros((50, 50), np.uint8), scale="big"), TypeError),
        (lambda: comic.detect(np.zeros((50, 50), np.uint8), threads=True), TypeError),
        (lambda: comic.imread("/nonexistent/image.png"), RuntimeError),
    ],
)
def test_bad_input_raises_with_the_cpp_message(call, error):
    with pytest.raises(error) as info:
        call()
    assert str(info.value)


def test_error_messages_name_the_problem():
    with pytest.raises(ValueError, match="unknown detector 'sift'"):
        comic.detect(np.zeros((50, 50), np.uint8), detector="sift")
    with pytest.raises(ValueError, match="unknown option 'sigma'"):
        comic.detect(np.zeros((50, 50), np.uint8), sigma=2.0)
    with pytest.raises(RuntimeError, match="/nonexistent/image.png"):
        comic.imread("/nonexistent/image.png")


def test_uniform_and_tiny_images_give_no_features():
    for image in (np.full((100, 100), 128, np.uint8), np.zeros((3, 3), np.uint8)):
        features, masks = comic.detect(image)
        assert len(features) == 0 and masks.shape == (0, 23, 23)
