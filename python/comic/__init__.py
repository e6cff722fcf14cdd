"""comic-sfm from Python: CoMIC features, patch matching, tracking and SfM.

Conventions follow cv2 and pycolmap: images are uint8 numpy arrays (H x W grey, or H x W x 3 BGR as
cv2.imread gives them), pixel centres at integer coordinates (OpenCV), results are numpy arrays
(structured where a row has named fields), options are keyword arguments named as the C++ Options
fields and the apps' flags (with underscores), and errors are exceptions carrying the C++ message:
ValueError for an invalid argument, TypeError for an argument or option of the wrong type,
RuntimeError for everything else (unreadable files, malformed data, an image beyond the pixel
budget), never an abort of the interpreter. The checks are the apps': thread counts at most the
machine's (0 = all), resize_height 0 or in [8, 16384], at most `max_pixels` pixels per image
(MAX_PIXELS by default, the apps' --max-pixels), inputs never overwritten. Long calls release the
GIL.

    import cv2, comic
    image = cv2.imread("frame.png")
    features, side_masks = comic.detect(image, detector="comic", scale=8.4)
    features["x"], features["response"]          # float32 columns, strongest first
"""

import json as _json

import numpy as _np

from . import _core

__version__ = _core.__version__
__all__ = [
    "FEATURE_DTYPE",
    "MATCH_DTYPE",
    "DETECTORS",
    "MAX_PIXELS",
    "Reconstruction",
    "Tracks",
    "detect",
    "export_colmap",
    "imread",
    "match",
    "reconstruct",
    "track",
]

#: One row per feature (frontend/feature.h). polarity: 1 bright, -1 dark, 0 none (baselines);
#: level: CoMIC's iso level, -1 for the baselines; cornerness: 0 for the baselines.
FEATURE_DTYPE = _np.dtype(
    [
        ("x", _np.float32),
        ("y", _np.float32),
        ("scale", _np.float32),
        ("response", _np.float32),
        ("cornerness", _np.float32),
        ("level", _np.int32),
        ("polarity", _np.int8),
    ]
)
#: One row per match: indices into the two feature arrays and the SSD cost (grey levels squared).
MATCH_DTYPE = _np.dtype([("index1", _np.int32), ("index2", _np.int32), ("cost", _np.float32)])
#: The detector names, in the paper's table order.
DETECTORS = tuple(_core.detector_names)
PATCH_SIZE = _core.patch_size
#: The default pixel budget per image (the apps' --max-pixels; io/core/pixel_budget.h).
MAX_PIXELS = _core.default_max_pixels


def _call(name, function, *args):
    """Calls the compiled `function`; a TypeError from pybind11's argument conversion ("incompatible
    function arguments", which would print every argument, whole image arrays included) becomes
    one short line naming the arguments' types."""
    try:
        return function(*args)
    except TypeError as error:
        if "incompatible function arguments" not in str(error):
            raise
        types = ", ".join(type(arg).__name__ for arg in args)
        raise TypeError("%s: an argument has the wrong type (got %s)" % (name, types)) from None


def _name(value, what):
    if not isinstance(value, str):
        raise TypeError(
            "%s must be a str (one of %s), got %s" % (what, ", ".join(DETECTORS), type(value).__name__)
        )
    return value


def _pack(columns, dtype):
    array = _np.empty(len(columns[dtype.names[0]]), dtype=dtype)
    for name in dtype.names:
        array[name] = columns[name]
    return array


def _features(columns):
    return _pack(columns, FEATURE_DTYPE), columns["side_masks"]


def _columns(features, what):
    if not isinstance(features, _np.ndarray) or features.dtype.names is None:
        raise TypeError(what + ": expected a structured array as returned by comic.detect")
    return {name: features[name] for name in features.dtype.names}


def imread(path, resize_height=0, color=False, max_pixels=MAX_PIXELS):
    """Reads an image as the apps do (io/image/image_io.h): grey uint8 H x W, or BGR H x W x 3 with
    color=True, resized to resize_height (0 = as stored). An image with more than max_pixels
    pixels after resizing is refused from its header, before it is decoded. Raises RuntimeError
    naming the file."""
    return _call(
        "imread", _core.imread, str(path), int(resize_height), bool(color), int(max_pixels)
    )


def detect(image, detector="comic", max_pixels=MAX_PIXELS, **options):
    """Detects features in `image` (uint8, grey or BGR; at most max_pixels pixels).

    Returns (features, side_masks): a structured array of FEATURE_DTYPE, strongest first, and a
    uint8 array of shape (N, 23, 23) labelling each feature's patch pixels by side of its iso-curve
    (1: ic+, 2: ic-, 0: neither; all 0 for detectors without side information). `options` are the
    named detector's options (e.g. scale=8.4, threads=2 for CoMIC; integration_sigma for Harris).
    """
    _name(detector, "detect: detector")
    return _features(
        _call("detect", _core.detect, _np.asarray(image), detector, options, int(max_pixels))
    )


def match(image1, features1, image2, features2, side_masks1=None, side_masks2=None, **options):
    """Mutual-best SSD patch matches between two feature sets (frontend/matching/patch_matcher.h).

    Options: search_radius (px, gate around each feature's position), cost ("full", "split" or
    "like-sides"; the split costs use the side masks), min_side_overlap, max_cost (the SSD
    threshold T; float("inf") keeps every mutual-best match). Returns a MATCH_DTYPE array.
    """
    columns = _call(
        "match",
        _core.match,
        _np.asarray(image1),
        _columns(features1, "match: features1"),
        side_masks1,
        _np.asarray(image2),
        _columns(features2, "match: features2"),
        side_masks2,
        options,
    )
    return _pack(columns, MATCH_DTYPE)


class Tracks:
    """Feature tracks over a sequence.

    features[i], side_masks[i]: frame i's features (as comic.detect returns them);
    observations: structured array (track, frame, feature), one row per observation, grouped by
    track with increasing frames; frame_names, image_size (width, height), detector.
    """

    def __init__(self, result):
        self.detector = result["detector"]
        self.image_size = tuple(result["image_size"])
        self.frame_names = list(result["frame_names"])
        packed = [_features(columns) for columns in result["features"]]
        self.features = [f for f, _ in packed]
        self.side_masks = [m for _, m in packed]
        self.observations = _pack(
            result,
            _np.dtype([("track", _np.int32), ("frame", _np.int32), ("feature", _np.int32)]),
        )

    @property
    def num_tracks(self):
        return int(self.observations["track"].max()) + 1 if len(self.observations) else 0

    def __len__(self):
        return self.num_tracks

    def __repr__(self):
        return "<comic.Tracks: %d frames, %d tracks, %d observations (%s)>" % (
            len(self.features),
            self.num_tracks,
            len(self.observations),
            self.detector,
        )


def track(frames, detector="comic", detector_options=None, callback=None, **options):
    """Detects and tracks features through `frames`: a folder of images or a video (path), or a
    sequence of uint8 images of one size.

    `options` are the tracker's, named as the apps' flags: search_radius, max_cost, cost,
    max_features, min_response, prediction ("none", "velocity", "coarse-to-fine"),
    unpredicted_radius, match_window, ...; for a path also resize_height, first, last, stride.
    `callback(done, total)` is called after each frame. Returns a Tracks.
    """
    _name(detector, "track: detector")
    if not isinstance(frames, str):
        frames = [_np.asarray(frame) for frame in frames]
    return Tracks(
        _call("track", _core.track, frames, detector, detector_options or {}, options, callback)
    )


class Reconstruction:
    """A reconstruction as comic_sfm writes it (COLMAP conventions: pixel centre of the top-left
    pixel at (0.5, 0.5), cam_from_world poses, ids from 1).

    cameras: structured (camera_id, model, width, height, params[4]); images: structured
    (image_id, camera_id, qvec[4] (w, x, y, z), tvec[3], name, num_points2D); points3D: structured
    (point3D_id, xyz[3], rgb[3], error, track_length); points2D: structured (image_id, x, y,
    point3D_id; -1 for none). status: "success" or why it failed; report: report.json's content
    (without the app's "options" and "track_building").
    """

    def __init__(self, core):
        self._core = core
        self.status = core.status
        self.report = _json.loads(core.report_json)
        columns = core.columns()
        cams = columns["cameras"]
        num_params = max([len(p) for p in cams["params"]] + [0])
        self.cameras = _np.empty(
            len(cams["camera_id"]),
            dtype=[
                ("camera_id", _np.uint32),
                ("model", "U32"),
                ("width", _np.int32),
                ("height", _np.int32),
                ("params", _np.float64, (num_params,)),
            ],
        )
        for name in ("camera_id", "model", "width", "height"):
            self.cameras[name] = cams[name]
        for i, params in enumerate(cams["params"]):
            self.cameras["params"][i, : len(params)] = params
        imgs = columns["images"]
        longest = max([len(n) for n in imgs["name"]] + [1])
        self.images = _np.empty(
            len(imgs["image_id"]),
            dtype=[
                ("image_id", _np.uint32),
                ("camera_id", _np.uint32),
                ("qvec", _np.float64, (4,)),
                ("tvec", _np.float64, (3,)),
                ("name", "U%d" % longest),
                ("num_points2D", _np.uint32),
            ],
        )
        for name in self.images.dtype.names:
            self.images[name] = imgs[name]
        pts = columns["points3D"]
        self.points3D = _np.empty(
            len(pts["point3D_id"]),
            dtype=[
                ("point3D_id", _np.uint64),
                ("xyz", _np.float64, (3,)),
                ("rgb", _np.uint8, (3,)),
                ("error", _np.float64),
                ("track_length", _np.uint32),
            ],
        )
        for name in self.points3D.dtype.names:
            self.points3D[name] = pts[name]
        self.points2D = _pack(
            columns["points2D"],
            _np.dtype(
                [
                    ("image_id", _np.uint32),
                    ("x", _np.float64),
                    ("y", _np.float64),
                    ("point3D_id", _np.int64),
                ]
            ),
        )

    def write(self, folder, model_format="both", ply_format="binary"):
        """Writes what comic_sfm writes into `folder`: cameras.txt, images.txt, points3D.txt
        (model_format "txt" or "both"), sparse/0/*.bin ("bin" or "both") and points.ply."""
        if model_format not in ("txt", "bin", "both"):
            raise ValueError(
                "model_format: unknown format '%s' (expected txt, bin or both)" % model_format
            )
        if self.status != "success":
            raise RuntimeError("reconstruction failed (%s): nothing to write" % self.status)
        if model_format != "bin":
            self._core.write_text(folder)
        if model_format != "txt":
            self._core.write_binary(folder + "/sparse/0")
        self._core.write_ply(folder + "/points.ply", ply_format)

    def __repr__(self):
        return "<comic.Reconstruction %s: %d cameras, %d images, %d points>" % (
            self.status,
            len(self.cameras),
            len(self.images),
            len(self.points3D),
        )


def reconstruct(
    path,
    detector="harris",
    detector_options=None,
    intrinsics=None,
    gt=None,
    gt_format="auto",
    callback=None,
    **options
):
    """Structure from motion on a frame sequence (folder of images or video), as comic_sfm.

    intrinsics: a file ('fx fy cx cy', 3x3 K or 3x4 P such as KITTI's calib.txt); else those of
    `gt` (ground-truth cameras: KITTI poses.txt, Middlebury *_par.txt, Strecha folder), else
    f = 1.2 max(w, h). `options` use comic_sfm's names: max_features, search_radius,
    unpredicted_radius, prediction, match_window, max_cost, threads (detection; 0 = one per
    core), resize_height, first, last, stride, ... `callback(event)` gets a dict after each registered frame (frame, frame_name,
    num_registered, num_frames, num_points3D, ...). Returns a Reconstruction; a sequence that
    cannot be reconstructed gives status != "success", not an exception.
    """
    _name(detector, "reconstruct: detector")
    core = _call(
        "reconstruct",
        _core.reconstruct,
        path,
        detector,
        detector_options or {},
        intrinsics or "",
        gt or "",
        gt_format,
        options,
        callback,
    )
    return Reconstruction(core)


def export_colmap(
    frames,
    database,
    detector="harris",
    detector_options=None,
    intrinsics=None,
    image_path=None,
    overwrite=False,
    **options
):
    """Tracks features through a folder of frames and writes a COLMAP 3.8 database, as
    comic_export_colmap (same options and defaults, which are comic_sfm's tracker's: the same
    tracks from the same folder; window=5, max_error, min_inliers, threads). Returns a summary
    dict with the `colmap mapper` command to run."""
    _name(detector, "export_colmap: detector")
    return _call(
        "export_colmap",
        _core.export_colmap,
        frames,
        database,
        detector,
        detector_options or {},
        intrinsics or "",
        image_path or "",
        bool(overwrite),
        options,
    )
