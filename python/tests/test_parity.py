"""comic.reconstruct and comic_sfm are two doors onto one run (sfm/run/reconstruction_run.h): the
same options must write the same files, byte for byte. The only fields that may differ are the
durations a run measures: report.json's and compare.json's "time_s" (its counts num_* stay) and the
comparison table's duration columns (wall time s, tracking s, mapping s, local BA s, global BA s, in
compare.md, compare.csv and compare.json's "table"), and in report.html the sections marked
"durations" (time per stage, the comparison's table and time chart) and the report.json it embeds.
They are stripped before comparing; every other byte of every file is compared as is."""

import json
import os
import re
import subprocess

import numpy as np
import pytest

import comic
from conftest import EXAMPLE, SOURCE_DIR, app

FRAMES = os.path.join(EXAMPLE, "image_l")
POSES = os.path.join(EXAMPLE, "poses.txt")
HERZ_JESU = os.path.join(SOURCE_DIR, "..", "shared", "data", "strecha_Herz-Jesu-P8", "images")
# The table columns that are durations (sfm/evaluation/sfm_report.cc).
TIME_COLUMNS = {"wall time s", "tracking s", "mapping s", "local BA s", "global BA s"}


def without_durations(value):
    """A report without its measured durations: time_s keeps only its counts (num_*), a table
    row loses its duration columns, the CPU seconds of a stage (image_set_matching's *_cpu_s)
    go."""
    if isinstance(value, dict):
        return {
            key: (
                {k: v for k, v in item.items() if k.startswith("num_")}
                if key == "time_s"
                else without_durations(item)
            )
            for key, item in value.items()
            if key not in TIME_COLUMNS and not key.endswith("_cpu_s")
        }
    if isinstance(value, list):
        return [without_durations(item) for item in value]
    return value


def table_without_durations(text, separator):
    rows = [line.split(separator) for line in text.splitlines()]
    header = [cell.strip() for cell in rows[0]]
    keep = [i for i, name in enumerate(header) if name not in TIME_COLUMNS]
    assert len(keep) < len(header), "the table has no duration columns any more: update the test"
    return [[row[i] for i in keep] for row in rows]


PAGE_DATA = re.compile(r'(<script type="application/json" id="comic-page-data">)(.*?)(</script>)',
                       re.S)


def page_without_durations(text):
    """report.html: its page (every byte but the data) and its data without the sections that
    hold measured durations and without the durations of the report.json it embeds."""
    match = PAGE_DATA.search(text)
    assert match, "report.html has no page data any more: update the test"
    data = json.loads(match.group(2))
    timed = [s for s in data["sections"] if s.get("durations")]
    assert timed, "report.html has no duration sections any more: update the test"
    data["sections"] = [without_durations(s) for s in data["sections"] if not s.get("durations")]
    return text[: match.start(2)] + text[match.end(2) :], data


def comparable(path):
    name = os.path.basename(path)
    with open(path, "rb") as f:
        data = f.read()
    if name in ("report.json", "compare.json"):
        report = json.loads(data)
        assert "time_s" in json.dumps(report), name + ": no durations any more: update the test"
        return without_durations(report)
    if name == "compare.md":
        return table_without_durations(data.decode(), "|")
    if name == "compare.csv":
        return table_without_durations(data.decode(), ",")
    if name == "report.html":
        return page_without_durations(data.decode())
    return data


def tree(root):
    return sorted(
        os.path.relpath(os.path.join(folder, name), root)
        for folder, _, names in os.walk(root)
        for name in names
    )


def assert_same_outputs(cli, python):
    assert tree(cli) == tree(python)
    assert "report.json" in " ".join(tree(cli))
    for name in tree(cli):
        assert comparable(os.path.join(cli, name)) == comparable(os.path.join(python, name)), name


def run_cli(*args):
    result = subprocess.run(
        [app("comic_sfm")] + [str(a) for a in args] + ["--quiet"],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    assert result.returncode == 0, result.stdout
    return result.stdout


def test_bundled_example_compare_with_ground_truth(tmp_path):
    run_cli(FRAMES, "--gt", POSES, "--compare", "--detectors", "harris,fast", "--output",
            tmp_path / "cli")
    runs = comic.reconstruct(
        FRAMES, gt=POSES, compare=True, detectors=["harris", "fast"], output=tmp_path / "python"
    )
    assert list(runs) == ["harris", "fast"]
    assert all(run.status == "success" for run in runs.values())
    assert_same_outputs(tmp_path / "cli", tmp_path / "python")
    assert (tmp_path / "python" / "compare.md").exists()
    # The in-memory result is what was written.
    written = json.loads((tmp_path / "python" / "harris" / "report.json").read_text())
    assert runs["harris"].report == written


def test_bundled_example_self_calibrated(tmp_path):
    # No calibration: COLMAP's SIMPLE_RADIAL guess, refined where the motion constrains it.
    out = run_cli(FRAMES, "--output", tmp_path / "cli", "--model-format", "both")
    assert "default: f = 1.2 max(w, h)" in out
    model = comic.reconstruct(FRAMES, output=tmp_path / "python")
    assert model.report["camera"]["prior"]["model"] == "SIMPLE_RADIAL"
    assert model.report["options"]["intrinsics"]["source"].startswith("default")
    assert_same_outputs(tmp_path / "cli", tmp_path / "python")


@pytest.mark.skipif(not os.path.isdir(HERZ_JESU), reason="needs ../shared/data (Herz-Jesu-P8)")
def test_herz_jesu_self_calibrated_as_the_command_line(tmp_path):
    # The case that drifted (issue 24): without calibration comic_sfm self-calibrates a
    # SIMPLE_RADIAL camera and registers 8/8; Python must do the same.
    run_cli(HERZ_JESU, "--resize-height", "683", "--output", tmp_path / "cli")
    model = comic.reconstruct(HERZ_JESU, resize_height=683, output=tmp_path / "python")
    assert model.status == "success" and len(model.images) == 8
    assert model.cameras["model"][0] == "SIMPLE_RADIAL"
    assert model.report["camera"]["refined"]
    assert abs(model.cameras["params"][0, 0] - 1230.0) > 100.0  # the guess f = 1230 was refined
    assert_same_outputs(tmp_path / "cli", tmp_path / "python")


def test_a_failed_run_writes_what_comic_sfm_writes(tmp_path):
    # Two identical frames: no parallax, no model; report.json with the diagnosis and tracks.db.
    frames = tmp_path / "frames"
    frames.mkdir()
    image = open(os.path.join(FRAMES, "000000.png"), "rb").read()
    for name in ("a.png", "b.png", "c.png"):
        (frames / name).write_bytes(image)
    cli = subprocess.run(
        [app("comic_sfm"), str(frames), "--quiet", "--output", str(tmp_path / "cli")],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert cli.returncode == 1
    model = comic.reconstruct(str(frames), output=str(tmp_path / "python"))
    assert model.status != "success" and len(model.points3D) == 0
    assert cli.stderr.strip() == "comic_sfm: error: " + model.failure.replace(
        str(tmp_path / "python"), str(tmp_path / "cli")
    )
    assert_same_outputs(tmp_path / "cli", tmp_path / "python")


# Reconstructions.write(folder) is comic_sfm's writer on the run: every file comic_sfm writes into
# --output, every model, in the input's pixels (not the working size of resize_height). Compared
# byte for byte but for report.json and report.html, which hold the run's measured times (and
# report.json the list of outputs that a run given output= writes, which write() does not).
WRITE_EXCLUDED = {"report.json", "report.html"}


@pytest.mark.parametrize(
    "frames, resize_height",
    [
        (FRAMES, 0),
        (FRAMES, 200),
        # The case that wrote the working size's cameras (1025x683) for 3072x2048 images.
        pytest.param(
            HERZ_JESU,
            683,
            marks=pytest.mark.skipif(
                not os.path.isdir(HERZ_JESU), reason="needs ../shared/data (Herz-Jesu-P8)"
            ),
        ),
    ],
)
def test_write_is_what_comic_sfm_writes(tmp_path, frames, resize_height):
    run_cli(frames, "--resize-height", resize_height, "--output", tmp_path / "cli")
    models = comic.reconstruct(frames, resize_height=resize_height)
    models.write(tmp_path / "python")
    assert tree(tmp_path / "cli") == tree(tmp_path / "python")
    compared = [name for name in tree(tmp_path / "cli") if name not in WRITE_EXCLUDED]
    assert {"cameras.txt", "points3D.txt", "sparse/0/images.bin", "points.ply"} <= set(compared)
    for name in compared:
        cli = (tmp_path / "cli" / name).read_bytes()
        assert cli == (tmp_path / "python" / name).read_bytes(), name
    # The arrays are the written model's: every model, the largest first, in the input's pixels.
    written = comic.Reconstruction(tmp_path / "cli")
    assert len(models) >= 1 and models[0].images.tobytes() == models.images.tobytes()
    assert np.array_equal(models.cameras["params"], written.cameras["params"])
    first = sorted(os.listdir(frames))[0]
    assert models.cameras["height"][0] == comic.imread(os.path.join(frames, first)).shape[0]
    assert [len(m.images) for m in models] == sorted((len(m.images) for m in models), reverse=True)


def test_write_refuses_the_frames_folder():
    models = comic.reconstruct(FRAMES, last=3)
    with pytest.raises(ValueError, match="FRAMES"):
        models.write(FRAMES)
