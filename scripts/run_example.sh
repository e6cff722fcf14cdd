#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the bundled example
# (examples/data/kitti06_000-011), writing its outputs to out/example/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build_dir=${COMIC_BUILD_DIR:-build}
mkdir -p out/example
"$build_dir"/bin/comic_inspect examples/data/kitti06_000-011/image_l \
  --contact-sheet out/example/contact_sheet.png
