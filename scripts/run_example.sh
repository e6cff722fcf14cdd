#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the bundled example
# (examples/data/kitti06_000-011), writing its outputs to out/example/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build_dir=${COMIC_BUILD_DIR:-build}
mkdir -p out/example
# Structure from motion on the 12 KITTI frames with every detector, measured against the clip's
# ground-truth poses (intrinsics from the calib.txt beside poses.txt): one table in
# out/example/compare.md (.csv, .json), and per detector a COLMAP text model, a PLY point cloud,
# report.json and trajectory.png in out/example/<detector>/.
"$build_dir"/bin/comic_sfm examples/data/kitti06_000-011/image_l \
  --gt examples/data/kitti06_000-011/poses.txt --compare --output out/example
