"""comic.match and comic.track: known displacements on shifted synthetic frames, the bundled
example read from its folder, progress callbacks, bad input raising."""

import os

import numpy as np
import pytest

import comic
from conftest import EXAMPLE, textured_scene


def shifted(image, dx, dy, fill=110):
    """`image` moved by (dx, dy) >= 0 pixels, the uncovered border filled."""
    out = np.full_like(image, fill)
    out[dy:, dx:] = image[: image.shape[0] - dy, : image.shape[1] - dx]
    return out


def test_matches_follow_a_known_shift():
    image1 = textured_scene(seed=4)
    image2 = shifted(image1, 3, 2)
    features1, masks1 = comic.detect(image1, detector="harris")
    features2, masks2 = comic.detect(image2, detector="harris")
    matches = comic.match(image1, features1, image2, features2, search_radius=10.0)
    assert matches.dtype == comic.MATCH_DTYPE
    assert len(matches) > 20
    dx = features2["x"][matches["index2"]] - features1["x"][matches["index1"]]
    dy = features2["y"][matches["index2"]] - features1["y"][matches["index1"]]
    correct = (np.abs(dx - 3) < 0.5) & (np.abs(dy - 2) < 0.5)
    assert correct.mean() > 0.9
    assert np.all(matches["cost"] <= 400.0)
    # One-to-one.
    assert len(np.unique(matches["index1"])) == len(matches)
    assert len(np.unique(matches["index2"])) == len(matches)


def test_split_cost_uses_the_side_masks():
    image1 = textured_scene(seed=5)
    image2 = shifted(image1, 2, 1)
    features1, masks1 = comic.detect(image1)
    features2, masks2 = comic.detect(image2)
    split = comic.match(
        image1, features1, image2, features2, masks1, masks2, cost="split", max_cost=float("inf")
    )
    full = comic.match(image1, features1, image2, features2, max_cost=float("inf"))
    assert len(split) > 10 and len(full) > 10
    # The split cost is the smaller one by construction (frontend/matching/patch_matcher.h).
    common = np.intersect1d(split["index1"], full["index1"])
    split_cost = split["cost"][np.searchsorted(split["index1"], common)]
    full_cost = full["cost"][np.searchsorted(full["index1"], common)]
    assert np.mean(split_cost) <= np.mean(full_cost)


def test_bad_match_input_raises():
    image = textured_scene()
    features, masks = comic.detect(image, detector="fast")
    with pytest.raises(TypeError):
        comic.match(image, [1, 2], image, features)
    with pytest.raises(ValueError, match="side masks"):
        comic.match(image, features, image, features, masks[:1], None)
    with pytest.raises(ValueError, match="cost"):
        comic.match(image, features, image, features, cost="sad")
    with pytest.raises(ValueError):
        comic.match(image, features, image, features, search_radius=-1.0)
    with pytest.raises(ValueError, match="no field 'scale'"):
        comic.match(image, features[["x", "y"]], image, features)


def test_track_frames_in_memory():
    base = textured_scene(height=220, width=260, seed=6)
    frames = [shifted(base, 2 * i, i) for i in range(4)]
    progress = []
    tracks = comic.track(
        frames, detector="harris", callback=lambda done, total: progress.append((done, total))
    )
    assert progress[-1] == (4, 4) and len(progress) == 4
    assert isinstance(tracks, comic.Tracks)
    assert len(tracks.features) == 4 and tracks.image_size == (260, 220)
    obs = tracks.observations
    assert obs.dtype.names == ("track", "frame", "feature")
    assert tracks.num_tracks > 20
    # Along every track the feature moves by (2, 1) per frame.
    moves = []
    for t in range(tracks.num_tracks):
        rows = obs[obs["track"] == t]
        assert np.all(np.diff(rows["frame"]) > 0)
        xy = [(tracks.features[f]["x"][k], tracks.features[f]["y"][k]) for _, f, k in rows]
        for (x0, y0), (x1, y1), (f0, f1) in zip(xy, xy[1:], zip(rows["frame"], rows["frame"][1:])):
            moves.append(((x1 - x0) / (f1 - f0), (y1 - y0) / (f1 - f0)))
    moves = np.array(moves)
    assert np.mean((np.abs(moves[:, 0] - 2) < 0.5) & (np.abs(moves[:, 1] - 1) < 0.5)) > 0.9


def test_track_a_folder_with_sequence_options():
    tracks = comic.track(
        os.path.join(EXAMPLE, "image_l"), detector="fast", last=3, max_features=300,
        prediction="velocity",
    )
    assert tracks.frame_names == ["000000.png", "000001.png", "000002.png", "000003.png"]
    assert all(len(f) <= 300 for f in tracks.features)
    assert tracks.num_tracks > 50
    again = comic.track(
        os.path.join(EXAMPLE, "image_l"), detector="fast", last=3, max_features=300,
        prediction="velocity",
    )
    assert np.array_equal(tracks.observations, again.observations)


def test_bad_track_input_raises():
    image = textured_scene()
    with pytest.raises(ValueError, match="differs in size"):
        comic.track([image, image[:100]])
    with pytest.raises(ValueError, match="no frames"):
        comic.track([])
    with pytest.raises(ValueError, match="prediction"):
        comic.track([image, image], prediction="psychic")
    with pytest.raises(ValueError, match="unknown option 'last'"):
        comic.track([image, image], last=1)  # sequence options need a path
    with pytest.raises(RuntimeError, match="no such file or folder"):
        comic.track("/nonexistent/frames")
    with pytest.raises(ZeroDivisionError):
        comic.track([image, image], detector="fast", callback=lambda done, total: 1 / 0)
