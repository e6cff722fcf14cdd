"""comic-sfm from Python: CoMIC features, patch matching, tracking and SfM.

Conventions follow cv2 and pycolmap: images are uint8 numpy arrays (H x W grey, or H x W x 3 BGR as
cv2.imread gives them), pixel centres at integer coordinates (OpenCV), results are numpy arrays
(structured where a row has named fields), options are keyword arguments named as the apps' flags
with underscores (comic_sfm --max-features -> max_features), and errors are exceptions carrying the
command line's message: ValueError for an invalid argument, TypeError for an argument or option of
the wrong type, RuntimeError for everything else (unreadable files, malformed data, an image beyond
the pixel budget), never an abort of the interpreter. The checks are the apps': thread counts at
most the machine's (0 = all), resize_height 0 or in [8, 16384], at most `max_pixels` pixels per
image (MAX_PIXELS by default, the apps' --max-pixels), outputs never over inputs. Long calls
release the GIL.

reconstruct() and export_colmap() run what comic_sfm and comic_export_colmap run (the library's
sfm/run/): the same options give the same files, byte for byte.

    import cv2, comic
    image = cv2.imread("frame.png")
    features, side_masks = comic.detect(image, detector="comic", scale=8.4)
    features["x"], features["response"]          # float32 columns, strongest first

    model = comic.reconstruct("frames/", output="out/sfm")   # as comic_sfm frames/ -o out/sfm
    model = comic.Reconstruction("out/sfm")                   # or any COLMAP model folder
"""

import json as _json
import os as _os
import textwrap as _textwrap

import numpy as _np

from . import _core

__version__ = _core.__version__
__all__ = [
    "FEATURE_DTYPE",
    "MATCH_DTYPE",
    "DETECTORS",
    "EXPORT_COLMAP_OPTIONS",
    "MAX_PIXELS",
    "RECONSTRUCT_OPTIONS",
    "Reconstruction",
    "Reconstructions",
    "TRACKER_OPTIONS",
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
#: The detector names, in the paper's table order (several may be joined by '+': "comic+hessian").
DETECTORS = tuple(_core.detector_names)
#: The side of a feature's patch in pixels (23).
PATCH_SIZE = _core.patch_size
#: The keyword options of reconstruct(): comic_sfm's long flags with underscores.
RECONSTRUCT_OPTIONS = tuple(sorted(_core.reconstruct_option_names()))
#: The keyword options of export_colmap(): comic_export_colmap's long flags with underscores.
EXPORT_COLMAP_OPTIONS = tuple(sorted(_core.export_colmap_option_names()))
#: The tracker's keyword options, shared by reconstruct(), export_colmap() and track(): the
#: tracker flags of comic_sfm and comic_export_colmap with underscores, in --help's order.
TRACKER_OPTIONS = tuple(entry["keyword"] for entry in _core.tracker_option_table())
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
            "%s must be a str (one of %s), got %s"
            % (what, ", ".join(DETECTORS), type(value).__name__)
        )
    return value


def _path(value, what):
    if not isinstance(value, (str, _os.PathLike)):
        raise TypeError("%s must be a str or os.PathLike, got %s" % (what, type(value).__name__))
    return _os.fspath(value)


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
        "imread", _core.imread, _path(path, "imread: path"), resize_height, bool(color), max_pixels
    )


def detect(image, detector="comic", max_pixels=MAX_PIXELS, **options):
    """Detects features in `image` (uint8, grey or BGR; at most max_pixels pixels).

    comic_detect's run (sfm/run/detect_run.h): the same options give the same features as
    `comic_detect IMAGE --json` on the same pixels. Returns (features, side_masks): a structured
    array of FEATURE_DTYPE, strongest first, and a uint8 array of shape (N, 23, 23) labelling each
    feature's patch pixels by side of its iso-curve (1: ic+, 2: ic-, 0: neither; all 0 for
    detectors without side information). `options` are the named detector's options: for CoMIC's
    two searches comic_detect's flags with underscores (listed below); for the baselines their
    fields (integration_sigma for Harris, ...); for every detector scale_levels, threads (0, the
    default: one per core; the features do not depend on it) and max_features (keep the strongest
    N; 0: all).
    """
    _name(detector, "detect: detector")
    return _features(
        _call("detect", _core.detect, _np.asarray(image), detector, options, max_pixels)
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
        """The number of tracks (track ids run from 0 to num_tracks - 1)."""
        return int(self.observations["track"].max()) + 1 if len(self.observations) else 0

    def __len__(self):
        """The number of tracks."""
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

    `options` are the tracker's, named as the apps' flags: every entry of the tracker table
    (reconstruct's docstring lists them, comic.TRACKER_OPTIONS names them; here the paper's
    protocol gives the defaults: no prediction, 20 px, all features), and cost, min_side_overlap,
    min_response, velocity_neighbours, velocity_neighbour_radius, coarse_factor, coarse_features;
    for a path also resize_height, first, last, stride; max_pixels for both. `callback(done, total)` is called after each frame. Returns a Tracks.
    """
    _name(detector, "track: detector")
    if isinstance(frames, _os.PathLike):
        frames = _os.fspath(frames)
    if not isinstance(frames, str):
        frames = [_np.asarray(frame) for frame in frames]
    return Tracks(
        _call("track", _core.track, frames, detector, detector_options or {}, options, callback)
    )


def _option_values(options):
    """Paths (os.PathLike) as strings and detector lists as comic_sfm's comma-separated text."""
    values = {}
    for name, value in options.items():
        if isinstance(value, _os.PathLike):
            value = _os.fspath(value)
        elif name == "detectors" and isinstance(value, (list, tuple)):
            value = ",".join(value)
        values[name] = value
    return values


class Reconstruction:
    """A COLMAP model as numpy arrays, read from a folder or made by reconstruct().

    Reconstruction(path) reads a model as pycolmap.Reconstruction(path) does: `path` itself when it
    holds cameras, images and points3D (.bin preferred over .txt), else its sparse/0/. So it opens
    comic_sfm's --output (and its report.json), COLMAP's sparse/0 and any text model. Raises
    RuntimeError naming the path when there is none.

    Conventions are COLMAP's: the centre of the top-left pixel at (0.5, 0.5), cam_from_world poses
    (qvec w, x, y, z; tvec), ids from 1.

    Attributes:
        cameras: structured array (camera_id, model, width, height, params[n]).
        images: structured array (image_id, camera_id, qvec[4], tvec[3], name, num_points2D).
        points3D: structured array (point3D_id, xyz[3], rgb[3], error, track_length).
        points2D: structured array (image_id, x, y, point3D_id), one row per 2-D point of every
            image; point3D_id is -1 for a point without a 3-D point.
        status: a run's status ("success", or why it failed: "no_initial_pair", ...); None for a
            model read without a report.json.
        report: report.json's content as a dict ({} without one).
        failure: a single detector's failed run: comic_sfm's error line (which check failed, by how
            much, what to try); "" otherwise.
        path: the folder the model was read from or written to ("" for a run without output).
    """

    def __init__(self, path):
        self._load(_core.read_reconstruction(_os.fspath(path)))

    @classmethod
    def _from_core(cls, core):
        reconstruction = cls.__new__(cls)
        reconstruction._load(core)
        return reconstruction

    def _load(self, core):
        self._core = core
        self.status = core.status or None
        self.report = _json.loads(core.report_json) if core.report_json else {}
        self.failure = core.failure
        self.path = core.path
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

    def _check_model(self):
        if self.status is not None and self.status != "success":
            raise RuntimeError("reconstruction failed (%s): nothing to write" % self.status)

    def write(self, folder, model_format="both", ply_format="binary"):
        """Writes this one model into `folder`: cameras.txt, images.txt, points3D.txt
        (model_format "txt" or "both"), sparse/0/*.bin ("bin" or "both") and points.ply
        (ply_format "binary" or "ascii"). A run's Reconstructions.write writes every model and
        the run's other files, as comic_sfm does. Raises ValueError for an unknown format and
        RuntimeError for a failed run's reconstruction (no model)."""
        if model_format not in ("txt", "bin", "both"):
            raise ValueError(
                "--model-format: unknown format '%s' (expected txt, bin or both)" % model_format
            )
        self._check_model()
        folder = _os.fspath(folder)
        if model_format != "bin":
            self._core.write_text(folder)
        if model_format != "txt":
            self._core.write_binary(_os.path.join(folder, "sparse", "0"))
        self._core.write_ply(_os.path.join(folder, "points.ply"), ply_format)

    def write_text(self, folder):
        """Writes cameras.txt, images.txt and points3D.txt into `folder` (COLMAP's text model)."""
        self._check_model()
        self._core.write_text(_os.fspath(folder))

    def write_binary(self, folder):
        """Writes cameras.bin, images.bin and points3D.bin into `folder` (COLMAP's binary model)."""
        self._check_model()
        self._core.write_binary(_os.fspath(folder))

    def write_ply(self, path, ply_format="binary"):
        """Writes the 3-D points with their colours as a PLY file ("binary" or "ascii")."""
        self._check_model()
        self._core.write_ply(_os.fspath(path), ply_format)

    def __repr__(self):
        return "<comic.Reconstruction %s: %d cameras, %d images, %d points>" % (
            self.status or "model",
            len(self.cameras),
            len(self.images),
            len(self.points3D),
        )


class Reconstructions(Reconstruction):
    """Every model of a run of reconstruct(), the largest first; it is also its largest model.

    A run may end with several models (the frames between them could not be linked): comic_sfm
    writes each one (sparse/0 the largest, sparse/1, ...). len(), indexing and iteration give them
    as Reconstruction objects, in the input's pixels; the attributes of Reconstruction (cameras,
    images, points3D, points2D, status, report, failure, path) are those of the largest model, as
    reconstruct() returned before it returned every model. A failed run holds no model (len 0).
    """

    def _load(self, core):
        super()._load(core)
        self.models = [Reconstruction._from_core(core.model(k)) for k in range(core.num_models())]

    def __len__(self):
        return len(self.models)

    def __bool__(self):
        return True

    def __getitem__(self, index):
        return self.models[index]

    def __iter__(self):
        return iter(self.models)

    def write(self, folder, model_format="both", ply_format="binary"):
        """Writes what `comic_sfm FRAMES --output folder` writes for this run, by comic_sfm's own
        writer (sfm/run/run_outputs.h) on the same run: every model in the input's pixels (the
        largest as text at the top and every one in sparse/<k>/ by model_format "txt", "bin" or
        "both"), points.ply (ply_format "binary" or "ascii"), trajectory.png, transforms.json,
        trajectory_tum.txt, report.html and report.json (whose "outputs" list, as in a run without
        output=, is absent); a failed run's report and tracks.db. Raises ValueError for an unknown
        format."""
        if model_format not in ("txt", "bin", "both"):
            raise ValueError(
                "--model-format: unknown format '%s' (expected txt, bin or both)" % model_format
            )
        if not self._core.has_run():
            return super().write(folder, model_format, ply_format)
        _call("write", self._core.write_outputs, _os.fspath(folder), model_format, ply_format)

    def __repr__(self):
        return "<comic.Reconstructions %s: %d models, the largest %d images, %d points>" % (
            self.status or "model",
            len(self.models),
            len(self.images),
            len(self.points3D),
        )


def reconstruct(frames, *, detector_options=None, callback=None, **options):
    """Structure from motion on a frame sequence (a folder of images or a video), as comic_sfm.

    The run is comic_sfm's (the library's sfm/run/reconstruction_run.h): the camera comes from
    `intrinsics`, else from the ground truth `gt`, else it is COLMAP's default SIMPLE_RADIAL guess
    (f = 1.2 max(w, h)) self-calibrated during the run unless fixed_intrinsics=True; the same
    options write the same files as `comic_sfm FRAMES --output ...`, byte for byte.

    `options` are comic_sfm's long flags with underscores (comic.RECONSTRUCT_OPTIONS; `comic_sfm
    --help` gives every meaning and default). A flag without a value is a bool (compare=True).
    The plain ones, each setting one field, are listed with their meanings and defaults at the
    end (the library's table, sfm/run/run_option_table.h); the others:
      detectors:  detector (default "harris"; "comic", "comic+hessian", ...), detectors
                  (comma-separated or a list); detector_options: the one detector's own settings
                  (e.g. {"scale": 8.4} for comic; not with compare), scale_levels.
      camera:     intrinsics (fx fy cx cy [k1 k2 p1 p2], 3x3 K, 3x4 P such as KITTI's calib.txt,
                  OpenCV .yml/.xml, COLMAP cameras.txt), camera_model.
      truth:      masks (non-zero mask pixels remove features), mask_keeps_nonzero (True: zero
                  ones do, COLMAP's convention), regions, boundary_band.
      frames:     resize_height, first, last, stride, max_pixels, allow_truncated.
      tracking:   matching ("auto", "sequential", "exhaustive", "window:K"), matcher
                  ("patches", "descriptors", "auto"), max_features,
                  search_radius, unpredicted_radius, prediction, coarse_radius, match_window,
                  track_conflicts, verify_min_gap, match_turned, max_cost, threads.
      outputs:    output (a folder: written as comic_sfm writes it, all or nothing; default None:
                  nothing written, unlike comic_sfm's out/sfm), colmap_db, overwrite, window,
                  max_error, min_inliers, colmap_threads, write_frames (True: images/ in output,
                  or a folder).
      quiet:      default True (a library call is silent); False prints comic_sfm's lines.

    `callback(event)` is called after each registered frame with a dict (detector, frame,
    frame_name, model, initial_pair, merged, num_registered, num_frames, num_points3D).

    Returns a Reconstructions: every model (the largest first, in the input's pixels), which is
    also a Reconstruction, the largest model; its write(folder) writes what comic_sfm writes. With
    compare=True a dict {detector: Reconstructions} in the order run. A sequence that cannot be
    reconstructed is not an exception: its Reconstruction has status != "success", no model, its
    report (with the diagnosis) and `failure`, comic_sfm's error line. Bad options raise ValueError
    (TypeError for a wrong type) with comic_sfm's message; unreadable input raises RuntimeError.
    """
    result = _call(
        "reconstruct",
        _core.reconstruct,
        _os.fspath(frames),
        _option_values(options),
        detector_options or {},
        callback,
    )
    if not options.get("quiet", True):
        for line in result["lines"]:
            print(line)
    runs = [Reconstructions._from_core(core) for core in result["runs"]]
    if options.get("compare", False):
        return {run.report["detector"]: run for run in runs}
    return runs[0]


def _option_doc(heading, entries):
    """Docstring paragraphs of a library option table: one per entry, the default in brackets
    (an entry of both CoMIC searches says so)."""
    lines = ["", "    %s (the library's table; the default in brackets):" % heading]
    for entry in entries:
        text = "%s [%r]: %s." % (entry["keyword"], entry["default"], entry["help"])
        if len(entry.get("detectors", ())) == 2:
            text = text.replace(": ", ": both searches: ", 1)
        lines += _textwrap.wrap(
            text, width=100, initial_indent="      ", subsequent_indent="          "
        )
    return "\n".join(lines) + "\n"


def _run_option_doc():
    return _option_doc("The plain options", _core.run_option_table())


def _tracker_option_doc():
    return _option_doc("The tracker's options, the run's defaults", _core.tracker_option_table())


def _detector_option_doc():
    return _option_doc("CoMIC's options", _core.detector_option_table())


# Without docstrings (python -OO) there is nothing to add to.
if reconstruct.__doc__:
    reconstruct.__doc__ = (
        reconstruct.__doc__.rstrip() + "\n" + _run_option_doc() + _tracker_option_doc()
    )
if detect.__doc__:
    detect.__doc__ = detect.__doc__.rstrip() + "\n" + _detector_option_doc()


def export_colmap(frames, colmap_db, *, detector_options=None, **options):
    """Tracks features through `frames` (a folder of images or a video) and writes them as a
    COLMAP 3.8 database at `colmap_db`, as comic_export_colmap (the library's
    sfm/run/colmap_export_run.h): the same options write the same database, and comic_sfm's
    colmap_db= with the same tracker options too.

    `options` are comic_export_colmap's long flags with underscores (comic.EXPORT_COLMAP_OPTIONS):
    overwrite, window, max_error, min_inliers, colmap_threads, intrinsics, camera_model, detector,
    matching, matcher and the tracker options (max_features, search_radius, ...), first, last, stride,
    resize_height (a video only), max_pixels, threads, image_path, sparse, write_frames (a video's
    frames; default images/ beside the database), quiet (default True; False prints
    comic_export_colmap's report). `detector_options`: the detector's own settings.

    Returns a dict: num_images, num_keypoints, num_matched_pairs, num_verified_pairs, num_matches,
    num_inlier_matches, known_intrinsics, num_tracks, num_observations, matching, frames_folder,
    image_path and mapper_command (the `colmap mapper` command to run). Raises ValueError for bad
    options and RuntimeError for input or outputs it cannot use (an existing database without
    overwrite=True), leaving the database and frames as they were.
    """
    return _call(
        "export_colmap",
        _core.export_colmap,
        _os.fspath(frames),
        _os.fspath(colmap_db),
        _option_values(options),
        detector_options or {},
    )


if export_colmap.__doc__:
    export_colmap.__doc__ = export_colmap.__doc__.rstrip() + "\n" + _tracker_option_doc()
