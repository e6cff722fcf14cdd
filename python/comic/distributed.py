"""comic-sfm beyond one machine: overlapping chunks of a video or image folder (several clips too)
reconstructed as Dask tasks, then merged into one model by their shared frames.

    python3 -m comic.distributed frames/ --output out/run --chunk-size 500 --overlap 50 --workers 2
    python3 -m comic.distributed a.mp4 b.mp4 --output out/run --scheduler tcp://host:8786

Each chunk is comic_sfm's run (comic.reconstruct) on frames [first, last] of one input; it writes
its model into OUTPUT/chunks/NNNN through a temporary folder renamed into place, so a task that
dies mid-chunk leaves nothing half written and its retry writes the same files (the run is
deterministic: the result does not depend on threads or on the worker). The merge
(sfm/chunk_model_merging.h, through comic._core) runs as one more task: a similarity per chunk
from the points its shared frames give both models, then a bounded bundle adjustment. OUTPUT gets
the merged model as comic_sfm writes one (cameras.txt, images.txt, points3D.txt, sparse/0/*.bin,
points.ply; further models in sparse/1 ...), report.json (each chunk's frames, time, worker,
registered frames, status and merge, and the run's status: `success` when the first model holds
at least 95 % of the frames and no chunk failed, else `partial`, naming the frames of the chunks
that failed for good) and report.html, the same as a page (sfm/run/distributed_run_page.h).
docs/distributed.md.
"""

import argparse
import json
import os
import shutil
import socket
import sys
import time
import uuid

from . import Reconstruction, _core, reconstruct

#: The fraction of the frames the first model must hold for `success` (comic_sfm's rule).
SUCCESS_FRACTION = 0.95


def plan_chunks(num_frames, chunk_size, overlap):
    """The chunks of a sequence of `num_frames` frames as (first, last) inclusive pairs: each
    `chunk_size` frames long (the last may be shorter, but never shorter than overlap + 2), each
    starting `chunk_size - overlap` frames after the one before, so that consecutive chunks share
    `overlap` frames."""
    if chunk_size < 2:
        raise ValueError("--chunk-size must be >= 2, got %d" % chunk_size)
    if overlap < 1 or overlap >= chunk_size:
        raise ValueError("--overlap must be in [1, chunk size - 1], got %d" % overlap)
    if num_frames < 1:
        raise ValueError("no frames to cut into chunks")
    step = chunk_size - overlap
    chunks = []
    first = 0
    while True:
        last = min(num_frames - 1, first + chunk_size - 1)
        chunks.append((first, last))
        if last == num_frames - 1:
            break
        first += step
    # A short tail has too few frames of its own to start a model: it joins the chunk before.
    if len(chunks) > 1 and chunks[-1][1] - chunks[-1][0] + 1 < overlap + 2:
        chunks.pop()
        chunks[-1] = (chunks[-1][0], num_frames - 1)
    return chunks


def make_chunk_specs(inputs, output, chunk_size, overlap, options):
    """One dict per chunk: what run_chunk needs (plain data, so that any worker can run it)."""
    specs = []
    for clip, path in enumerate(inputs):
        names = _core.frame_names(os.fspath(path))
        # Clips may name their frames alike: frames of the second clip on are prefixed.
        prefix = "" if len(inputs) == 1 else "clip%d/" % clip
        for first, last in plan_chunks(len(names), chunk_size, overlap):
            index = len(specs)
            specs.append(
                {
                    "index": index,
                    "clip": clip,
                    "input": os.path.abspath(os.fspath(path)),
                    "first": first,
                    "last": last,
                    "frames": [prefix + name for name in names[first : last + 1]],
                    "name_prefix": prefix,
                    "path": os.path.join(os.path.abspath(output), "chunks", "%04d" % index),
                    "options": dict(options),
                }
            )
    return specs


def _worker_name():
    try:
        from distributed import get_worker

        return get_worker().address
    except (ImportError, ValueError):
        return "%s:%d" % (socket.gethostname(), os.getpid())


def _simulate_failure(spec, hook):
    """Test hook: the first attempt of chunk hook["chunk"] fails after writing its temporary
    folder (hook["how"] "raise": the task raises; "exit": the worker process dies), once: the
    marker file hook["marker"] records that it happened."""
    if not hook or hook.get("chunk") != spec["index"] or os.path.exists(hook["marker"]):
        return
    with open(hook["marker"], "w") as marker:
        marker.write("failed once\n")
    if hook.get("how") == "exit":
        os._exit(1)
    raise RuntimeError("simulated failure of chunk %d" % spec["index"])


def run_chunk(spec, failure_hook=None):
    """Reconstructs one chunk (a Dask task): comic.reconstruct on frames [first, last] into a
    temporary folder beside spec["path"], renamed into place when whole. A chunk already in place
    (an earlier attempt finished) is kept: the run is deterministic, so its files are the ones a
    new run would write. Returns the chunk's record for report.json."""
    start = time.time()
    record = {
        key: spec[key]
        for key in ("index", "clip", "input", "first", "last", "path", "frames", "name_prefix")
    }
    record["worker"] = _worker_name()
    if not os.path.isdir(spec["path"]):
        os.makedirs(os.path.dirname(spec["path"]), exist_ok=True)
        staging = "%s.tmp-%s" % (spec["path"], uuid.uuid4().hex)
        try:
            reconstruct(
                spec["input"],
                output=staging,
                first=spec["first"],
                last=spec["last"],
                quiet=True,
                **spec["options"]
            )
            _simulate_failure(spec, failure_hook)
            try:
                os.rename(staging, spec["path"])
            except OSError:
                # Another attempt of this chunk got there first with the same files.
                if not os.path.isdir(spec["path"]):
                    raise
        finally:
            shutil.rmtree(staging, ignore_errors=True)
    try:
        model = Reconstruction(spec["path"])
        record["status"] = model.status or "success"
        record["registered_frames"] = [spec["name_prefix"] + n for n in model.images["name"]]
    except RuntimeError:
        # A run that found no model still wrote its report.json, with why.
        with open(os.path.join(spec["path"], "report.json")) as report:
            record["status"] = json.load(report).get("status", "failed")
        record["registered_frames"] = []
    record["time_s"] = round(time.time() - start, 3)
    return record


def _remove_staging_left_by_dead_workers(output):
    """A worker killed mid-chunk leaves its temporary folder (its finally never ran); once every
    chunk task is over no attempt can still be writing one."""
    chunks = os.path.join(output, "chunks")
    for name in sorted(os.listdir(chunks)) if os.path.isdir(chunks) else []:
        if ".tmp-" in name:
            shutil.rmtree(os.path.join(chunks, name), ignore_errors=True)


def merge_chunks(records, output, global_ba_max_images):
    """Merges the chunks' models (a Dask task, on one worker): writes the models into
    output/merged.tmp-*/k and returns (the folder, the merge's summary)."""
    start = time.time()
    usable = [r for r in records if r.get("registered_frames")]
    staging = os.path.join(os.path.abspath(output), "merged.tmp-%s" % uuid.uuid4().hex)
    summary = _core.merge_chunk_models(
        [r["path"] for r in usable],
        [r["name_prefix"] for r in usable],
        staging,
        global_ba_max_images,
    )
    summary["chunk_indices"] = [r["index"] for r in usable]
    summary["time_s"] = round(time.time() - start, 3)
    summary["worker"] = _worker_name()
    return staging, summary


def _write_outputs(output, staging, summary, records, specs, started):
    """The merged models as comic_sfm writes its model, report.json and report.html."""
    models = summary["models"]
    first_model = set(Reconstruction(models[0]["path"]).images["name"]) if models else set()
    for k, model in enumerate(models):
        merged = Reconstruction(model["path"])
        if k == 0:
            merged.write(output, model_format="both")
        else:
            merged.write_binary(os.path.join(output, "sparse", str(k)))
    shutil.rmtree(staging, ignore_errors=True)

    frames = []
    for spec in specs:
        frames.extend(f for f in spec["frames"] if f not in frames)
    merge_by_chunk = dict(zip(summary["chunk_indices"], summary["chunks"]))
    chunks, failed = [], []
    for spec, record in zip(specs, records):
        entry = dict(record)
        entry["num_frames"] = len(spec["frames"])
        entry["num_registered"] = len(record.get("registered_frames", []))
        entry["merge"] = merge_by_chunk.get(spec["index"])
        if record["status"] == "failed":
            failed.append({"index": spec["index"], "frames": spec["frames"]})
        chunks.append(entry)
    registered = [f for f in frames if f in first_model]
    complete = not failed and len(registered) >= SUCCESS_FRACTION * len(frames)
    report = {
        "status": "success" if complete else "partial",
        "num_frames": len(frames),
        "num_registered": len(registered),
        "unregistered_frames": [f for f in frames if f not in first_model],
        "failed_chunks": failed,
        "chunks": chunks,
        "merge": {k: summary[k] for k in ("time_s", "worker", "adjustments")},
        "models": [
            {"num_images": m["num_images"], "num_points3D": m["num_points3D"]} for m in models
        ],
        "wall_time_s": round(time.time() - started, 3),
    }
    staged_report = os.path.join(output, "report.json.tmp")
    with open(staged_report, "w") as out:
        json.dump(report, out, indent=2)
        out.write("\n")
    os.replace(staged_report, os.path.join(output, "report.json"))
    # The page comic_sfm's report.html is made of, drawn from the same JSON (so it says what
    # report.json says), written atomically by the library.
    _core.write_distributed_run_page(
        os.path.join(output, "report.html"), json.dumps(report, sort_keys=True)
    )
    return report


def run(
    inputs,
    output,
    client,
    chunk_size=500,
    overlap=50,
    retries=2,
    global_ba_max_images=300,
    failure_hook=None,
    **options
):
    """Cuts `inputs` (folders or videos) into chunks, reconstructs them on `client`'s cluster,
    merges them on one worker and writes OUTPUT (see the module's docstring). `options` are
    comic.reconstruct's (comic_sfm's flags with underscores), the same for every chunk; each chunk
    runs on one thread unless `threads` says otherwise. A chunk task that fails is retried
    `retries` times (Dask's retries; a worker that dies is replaced and its task rescheduled by the
    scheduler), then counted as failed. Returns report.json's content."""
    from distributed import wait

    started = time.time()
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    options.setdefault("threads", 1)
    specs = make_chunk_specs(inputs, output, chunk_size, overlap, options)
    os.makedirs(output, exist_ok=True)
    futures = [
        client.submit(
            run_chunk,
            spec,
            failure_hook,
            key="chunk-%04d-%s" % (spec["index"], uuid.uuid4().hex),
            retries=retries,
            pure=False,
        )
        for spec in specs
    ]
    wait(futures)
    _remove_staging_left_by_dead_workers(output)
    records = []
    for spec, future in zip(specs, futures):
        if future.status == "finished":
            records.append(future.result())
        else:
            record = {
                k: spec[k]
                for k in ("index", "clip", "input", "first", "last", "frames", "name_prefix")
            }
            record.update(
                {
                    "path": None,
                    "status": "failed",
                    "registered_frames": [],
                    "error": repr(future.exception()),
                }
            )
            records.append(record)
    staging, summary = client.submit(
        merge_chunks, records, output, global_ba_max_images, pure=False
    ).result()
    return _write_outputs(output, staging, summary, records, specs, started)


def _parse_options(pairs):
    """--set NAME=VALUE pairs as comic.reconstruct's keywords: ints, floats and true/false as
    such, anything else as text."""
    options = {}
    for pair in pairs:
        if "=" not in pair:
            raise SystemExit("--set expects NAME=VALUE, got '%s'" % pair)
        name, value = pair.split("=", 1)
        name = name.lstrip("-").replace("-", "_")
        for convert in (int, float):
            try:
                value = convert(value)
                break
            except ValueError:
                pass
        if value in ("true", "false"):
            value = value == "true"
        options[name] = value
    return options


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python3 -m comic.distributed",
        description="Reconstruct a video or image folder (or several clips) as overlapping chunks "
        "on a Dask cluster and merge them into one model by their shared frames. Writes "
        "OUTPUT/cameras.txt, images.txt, points3D.txt, sparse/0, points.ply, report.json and "
        "report.html (each chunk's time, worker and registered frames; status success or "
        "partial); the chunks' own "
        "models stay in OUTPUT/chunks/.",
        epilog="example: python3 -m comic.distributed frames/ -o out/run --chunk-size 500 "
        "--overlap 50 --workers 2. Exit code 0 for success, 1 for partial. docs/distributed.md",
    )
    parser.add_argument("inputs", nargs="+", help="image folders or videos (each one clip)")
    parser.add_argument("--output", "-o", required=True, help="output folder (shared by workers)")
    parser.add_argument("--chunk-size", type=int, default=500, help="frames per chunk [500]")
    parser.add_argument("--overlap", type=int, default=50, help="frames shared by neighbours [50]")
    cluster = parser.add_mutually_exclusive_group()
    cluster.add_argument("--scheduler", help="a running Dask scheduler's address (tcp://host:8786)")
    cluster.add_argument(
        "--workers",
        type=int,
        default=1,
        help="without --scheduler: a LocalCluster of this many worker processes [1]",
    )
    parser.add_argument("--retries", type=int, default=2, help="retries of a failed chunk [2]")
    parser.add_argument(
        "--global-ba-max-images",
        type=int,
        default=300,
        help="frames per window of the merged model's adjustment (0: all at once, -1: none) [300]",
    )
    parser.add_argument("--intrinsics", help="as comic_sfm --intrinsics")
    parser.add_argument("--detector", help="as comic_sfm --detector [harris]")
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="any other comic_sfm option for every chunk, e.g. --set matcher=patches (repeatable)",
    )
    args = parser.parse_args(argv)
    options = _parse_options(args.set)
    for name in ("intrinsics", "detector"):
        if getattr(args, name) is not None:
            options[name] = getattr(args, name)

    from distributed import Client, LocalCluster

    if args.scheduler:
        client = Client(args.scheduler)
    else:
        client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1))
    with client:
        report = run(
            args.inputs,
            args.output,
            client,
            chunk_size=args.chunk_size,
            overlap=args.overlap,
            retries=args.retries,
            global_ba_max_images=args.global_ba_max_images,
            **options
        )
    print(
        "%s: %d/%d frames in the first model, %d chunks (%d failed), %.1f s -> %s"
        % (
            report["status"],
            report["num_registered"],
            report["num_frames"],
            len(report["chunks"]),
            len(report["failed_chunks"]),
            report["wall_time_s"],
            os.path.join(args.output, "report.json"),
        )
    )
    return 0 if report["status"] == "success" else 1


if __name__ == "__main__":
    sys.exit(main())
