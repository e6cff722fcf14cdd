"""comic.distributed on a Dask LocalCluster with the bundled KITTI example (12 frames): the chunks
merged into one model of every frame, byte for byte the same on a second run, after a chunk task
that failed and was retried, and after a worker process that died mid-chunk; a chunk that fails
for good gives `partial` naming its frames; report.html shows each chunk's worker, time,
registered frames and merge, and the merged model's counts."""

import json
import os
import re

import pytest

pytest.importorskip("dask", reason="python3-dask is not installed (scripts/install_deps.sh)")
distributed = pytest.importorskip(
    "distributed", reason="python3-distributed is not installed (scripts/install_deps.sh)"
)

import comic  # noqa: E402
from comic import distributed as comic_distributed  # noqa: E402
from conftest import EXAMPLE  # noqa: E402

FRAMES = os.path.join(EXAMPLE, "image_l")
CALIB = os.path.join(EXAMPLE, "calib.txt")
MODEL_FILES = [
    "cameras.txt",
    "images.txt",
    "points3D.txt",
    "sparse/0/cameras.bin",
    "sparse/0/images.bin",
    "sparse/0/points3D.bin",
]
# 12 frames in chunks of 5 sharing 1: frames 0-4, 4-8 and 8-11, three chunks.
CHUNKING = {"chunk_size": 5, "overlap": 1}


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=":0"
    )
    with distributed.Client(cluster) as dask_client:
        yield dask_client
    cluster.close()


PAGE_DATA = re.compile(r'<script type="application/json" id="comic-page-data">(.*?)</script>', re.S)


def page_data(path):
    """report.html's data: the JSON its page is drawn from ({title, subtitle, sections})."""
    text = path.read_text(encoding="utf-8")
    assert text.startswith("<!DOCTYPE html>")
    # Self-contained: nothing is fetched from elsewhere.
    assert not re.search(r'<(script|link|img)[^>]+(src|href)="(https?:)?//', text)
    match = PAGE_DATA.search(text)
    assert match, "report.html holds no page data"
    return json.loads(match.group(1))


def section(data, title):
    found = [s for s in data["sections"] if s.get("title") == title]
    assert len(found) == 1, "report.html has %d sections '%s'" % (len(found), title)
    return found[0]


def table_rows(data, title):
    """The rows of the page's table `title` as dicts keyed by its columns."""
    table = section(data, title)
    assert table["type"] == "table"
    return [dict(zip(table["columns"], row)) for row in table["rows"]]


def run_example(client, output, **kwargs):
    return comic_distributed.run(
        FRAMES, str(output), client, intrinsics=CALIB, **CHUNKING, **kwargs
    )


def model_bytes(folder):
    return {name: (folder / name).read_bytes() for name in MODEL_FILES}


@pytest.fixture(scope="module")
def first_run(client, tmp_path_factory):
    output = tmp_path_factory.mktemp("distributed") / "run"
    return output, run_example(client, output)


def test_plan_chunks_overlap_and_cover():
    assert comic_distributed.plan_chunks(12, 5, 1) == [(0, 4), (4, 8), (8, 11)]
    assert comic_distributed.plan_chunks(12, 4, 1) == [(0, 3), (3, 6), (6, 9), (9, 11)]
    # A tail too short to start a model of its own joins the chunk before.
    assert comic_distributed.plan_chunks(10, 5, 2) == [(0, 4), (3, 7), (6, 9)]
    assert comic_distributed.plan_chunks(9, 5, 2) == [(0, 4), (3, 8)]
    assert comic_distributed.plan_chunks(3, 5, 1) == [(0, 2)]
    with pytest.raises(ValueError, match="--overlap"):
        comic_distributed.plan_chunks(12, 4, 4)


def test_chunks_merge_into_one_model_of_every_frame(first_run):
    output, report = first_run
    assert report["status"] == "success"
    assert len(report["chunks"]) == 3
    assert [(c["first"], c["last"]) for c in report["chunks"]] == [(0, 4), (4, 8), (8, 11)]
    for chunk in report["chunks"]:
        assert chunk["status"] == "success"
        assert chunk["num_registered"] == chunk["num_frames"]
        assert chunk["worker"]
        assert chunk["time_s"] > 0
        assert os.path.isdir(chunk["path"])
    # Every chunk after the first joined the first one's model through its one shared frame.
    assert [c["merge"]["model_index"] for c in report["chunks"]] == [0, 0, 0]
    assert [c["merge"]["num_shared_frames"] for c in report["chunks"]] == [0, 1, 1]
    assert len(report["models"]) == 1
    assert report["num_frames"] == 12 and report["num_registered"] == 12
    assert report["unregistered_frames"] == [] and report["failed_chunks"] == []
    model = comic.Reconstruction(str(output))
    assert sorted(model.images["name"]) == sorted(os.listdir(FRAMES))
    assert len(model.points3D) > 100
    on_disk = json.loads((output / "report.json").read_text())
    assert on_disk["status"] == "success" and on_disk["num_registered"] == 12
    # Nothing half written is left behind.
    assert not [n for n in os.listdir(output / "chunks") if ".tmp-" in n]
    assert not [n for n in os.listdir(output) if ".tmp" in n]


def test_merged_model_is_close_to_the_truth(first_run):
    """The merge puts the chunks in one frame: the camera centres fit KITTI's poses up to a
    similarity within a few centimetres over the 12 frames (about 9 m)."""
    import numpy as np

    output, _ = first_run
    model = comic.Reconstruction(str(output))
    poses = np.loadtxt(os.path.join(EXAMPLE, "poses.txt")).reshape(-1, 3, 4)
    order = np.argsort(model.images["name"])
    estimated = []
    for i in order:
        w, x, y, z = model.images["qvec"][i]
        rotation = np.array(
            [
                [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
            ]
        )
        estimated.append(-rotation.T @ model.images["tvec"][i])
    estimated = np.array(estimated)
    truth = poses[:, :, 3]
    # Umeyama: the similarity taking the estimated centres onto the true ones.
    mu_e, mu_t = estimated.mean(0), truth.mean(0)
    e, t = estimated - mu_e, truth - mu_t
    u, s, vt = np.linalg.svd(t.T @ e / len(e))
    d = np.eye(3)
    d[2, 2] = np.sign(np.linalg.det(u @ vt))
    rotation = u @ d @ vt
    scale = np.trace(np.diag(s) @ d) / (e**2).sum(1).mean()
    aligned = scale * (rotation @ e.T).T + mu_t
    ate = np.sqrt(((aligned - truth) ** 2).sum(1).mean())
    assert ate < 0.1


def test_same_run_twice_gives_the_same_files(client, first_run, tmp_path):
    output, _ = first_run
    again = tmp_path / "again"
    report = run_example(client, again)
    assert report["num_registered"] == 12
    assert model_bytes(again) == model_bytes(output)


def test_failed_chunk_task_is_retried_with_the_same_result(client, first_run, tmp_path):
    output, _ = first_run
    marker = tmp_path / "failed_once"
    retried = tmp_path / "retried"
    hook = {"chunk": 1, "marker": str(marker), "how": "raise"}
    report = run_example(client, retried, failure_hook=hook)
    assert marker.exists(), "the simulated failure did not happen"
    assert report["status"] == "success" and report["failed_chunks"] == []
    assert model_bytes(retried) == model_bytes(output)


def test_chunk_failing_for_good_gives_partial_naming_its_frames(client, tmp_path):
    hook = {"chunk": 2, "marker": str(tmp_path / "failed_once"), "how": "raise"}
    report = run_example(client, tmp_path / "failed", failure_hook=hook, retries=0)
    assert report["status"] == "partial"
    names = sorted(os.listdir(FRAMES))
    assert report["failed_chunks"] == [{"index": 2, "frames": names[8:12]}]
    assert report["chunks"][2]["status"] == "failed"
    assert "simulated failure" in report["chunks"][2]["error"]
    # The other chunks' frames are still merged into one model.
    assert report["num_registered"] == 9
    assert report["unregistered_frames"] == names[9:12]
    assert sorted(comic.Reconstruction(str(tmp_path / "failed")).images["name"]) == names[:9]


def test_worker_killed_mid_chunk_gives_the_same_model(first_run, tmp_path):
    """A worker process that dies mid-chunk (after writing its temporary folder): the nanny
    restarts it, the scheduler runs the chunk again, and the model is the same byte for byte."""
    output, _ = first_run
    marker = tmp_path / "killed_once"
    hook = {"chunk": 1, "marker": str(marker), "how": "exit"}
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
    )
    with distributed.Client(cluster) as process_client:
        report = run_example(process_client, tmp_path / "killed", failure_hook=hook)
    cluster.close()
    assert marker.exists(), "no worker was killed"
    assert report["status"] == "success"
    assert model_bytes(tmp_path / "killed") == model_bytes(output)
    assert not [n for n in os.listdir(tmp_path / "killed" / "chunks") if ".tmp-" in n]


def test_report_page_shows_every_chunk_and_the_merged_model(first_run):
    output, report = first_run
    data = page_data(output / "report.html")
    facts = {f["label"]: f for f in section(data, "Summary")["facts"]}
    assert facts["status"]["value"] == "success" and facts["status"]["tone"] == "good"
    assert facts["registered"]["value"].startswith("12 of 12 frames")
    assert facts["chunks"]["value"] == "3 (0 failed)"
    assert facts["first model"]["value"] == "12 frames, %d 3-D points" % (
        report["models"][0]["num_points3D"]
    )
    assert report["merge"]["worker"] in facts["merge"]["value"]
    rows = table_rows(data, "Chunks")
    assert len(rows) == len(report["chunks"]) == 3
    for row, chunk in zip(rows, report["chunks"]):
        assert row["chunk"] == str(chunk["index"])
        assert row["clip"] == "0"
        assert row["frames"] == "%d–%d (%d frames)" % (
            chunk["first"],
            chunk["last"],
            chunk["last"] - chunk["first"] + 1,
        )
        assert row["worker"] == chunk["worker"]
        assert float(row["time (s)"]) == pytest.approx(chunk["time_s"], abs=0.006)
        assert row["status"] == "success"
        assert row["registered"] == str(chunk["num_registered"])
        merged = "began model 0" if chunk["index"] == 0 else "joined model 0 through 1 shared frame"
        assert row["merge"].startswith(merged)
    # Each row links to the chunk's own comic_sfm page, which is there.
    links = section(data, "Chunks")["links"]
    assert links == ["chunks/%04d/report.html" % i for i in range(3)]
    assert all((output / link).is_file() for link in links)
    models = table_rows(data, "Merged models")
    assert models == [
        {
            "model": "0",
            "folder": ". and sparse/0",
            "frames": "12",
            "3-D points": str(report["models"][0]["num_points3D"]),
        }
    ]
    # The page embeds the report.json it was drawn from.
    on_disk = json.loads((output / "report.json").read_text())
    assert section(data, "report.json")["document"] == on_disk
    assert not [n for n in os.listdir(output) if ".tmp" in n]


def test_report_page_of_a_partial_run_names_the_failed_chunk(client, tmp_path):
    hook = {"chunk": 1, "marker": str(tmp_path / "failed_once"), "how": "raise"}
    output = tmp_path / "failed"
    report = comic_distributed.run(
        FRAMES, str(output), client, intrinsics=CALIB, retries=0, failure_hook=hook, **CHUNKING
    )
    assert report["status"] == "partial"
    data = page_data(output / "report.html")
    facts = {f["label"]: f for f in section(data, "Summary")["facts"]}
    assert facts["status"]["value"] == "partial" and facts["status"]["tone"] == "warning"
    assert facts["chunks"]["value"] == "3 (1 failed)"
    notice = section(data, "Chunks that failed for good")
    assert notice["tone"] == "bad" and "Chunk 1 (clip 0, frames 4–8" in notice["text"]
    assert "simulated failure" in notice["text"]
    rows = table_rows(data, "Chunks")
    assert [r["status"] for r in rows] == ["success", "failed", "success"]
    assert rows[1]["registered"] == "0" and rows[1]["merge"] == "not merged: the chunk failed"
    # Chunk 2 shares no frame with chunk 0: it begins a model of its own, and says why.
    assert rows[2]["merge"].startswith("began model 1: ")
    assert [m["frames"] for m in table_rows(data, "Merged models")] == ["5", "4"]


def test_two_clips_are_two_models_until_linked_by_appearance(client, tmp_path):
    """The bundled example given twice, as two clips: frames are named clipN/..., each clip's
    chunks are merged through their shared frames, but the second clip shares no frame with the
    first, so it begins a model of its own (sparse/1) and the run is `partial`. Linking clips
    that see the same place by appearance is not done yet (docs/distributed.md): when it is, this
    test should expect one model of 24 frames and `success`."""
    output = tmp_path / "two_clips"
    report = comic_distributed.run(
        [FRAMES, FRAMES], str(output), client, intrinsics=CALIB, **CHUNKING
    )
    names = sorted(os.listdir(FRAMES))
    assert [c["clip"] for c in report["chunks"]] == [0, 0, 0, 1, 1, 1]
    assert report["chunks"][3]["frames"] == ["clip1/" + n for n in names[0:5]]
    assert report["num_frames"] == 24 and report["num_registered"] == 12
    assert report["status"] == "partial" and report["failed_chunks"] == []
    assert report["unregistered_frames"] == ["clip1/" + n for n in names]
    assert [c["merge"]["model_index"] for c in report["chunks"]] == [0, 0, 0, 1, 1, 1]
    assert report["chunks"][3]["merge"]["started_model"]
    assert report["chunks"][3]["merge"]["reason"] == "no frame registered in the model before"
    assert [m["num_images"] for m in report["models"]] == [12, 12]
    # The same frames in the same chunks: the second model is the first one's, renamed.
    assert report["models"][0]["num_points3D"] == report["models"][1]["num_points3D"]
    first = comic.Reconstruction(str(output))
    second = comic.Reconstruction(str(output / "sparse" / "1"))
    assert sorted(first.images["name"]) == ["clip0/" + n for n in names]
    assert sorted(second.images["name"]) == ["clip1/" + n for n in names]

    data = page_data(output / "report.html")
    facts = {f["label"]: f["value"] for f in section(data, "Summary")["facts"]}
    assert facts["clips"] == "2" and facts["models"].startswith("2 ")
    assert facts["registered"].startswith("12 of 24 frames (50 %)")
    rows = table_rows(data, "Chunks")
    assert [r["clip"] for r in rows] == ["0", "0", "0", "1", "1", "1"]
    assert rows[3]["merge"] == "began model 1: no frame registered in the model before"
    assert rows[4]["merge"].startswith("joined model 1 through 1 shared frame")
    assert [(m["folder"], m["frames"]) for m in table_rows(data, "Merged models")] == [
        (". and sparse/0", "12"),
        ("sparse/1", "12"),
    ]
    left_out = section(data, "Frames left out")
    assert left_out["text"].startswith("12 frames are not in the first model: clip1/" + names[0])
