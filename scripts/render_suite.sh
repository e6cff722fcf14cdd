#!/usr/bin/env bash
# Renders the fixed suite of docs/rendered_benchmark.md (scene files in scenes/, images never
# committed) into OUT (default out/suite), with textures cut from photographs of ../shared/data,
# and prints each scene's timing (comic_render's CPU seconds, and wall time):
#   street_drive_500  500-frame drive with turns, poles and trees      (+ 4 stereo pairs)
#   loop_drive_2000   2000 frames once around a block, back to the start
#   orbit_object      360-frame orbit of an object before a far backdrop (+ 4 stereo pairs)
#   handheld_walk     300-frame sideways handheld walk past boxes
#   lego_composite    the 100 NeRF lego views over lego_background seen by the same cameras
# Usage: scripts/render_suite.sh [OUT] [SCENE...]   (SCENE: names above; default all)
# Depth is written as PFM (float metres): the drives see farther than a 16-bit PNG holds.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${COMIC_BUILD_DIR:-build}
out=${1:-out/suite}
shift || true
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(street_drive_500 loop_drive_2000 orbit_object handheld_walk lego_composite)
data=../shared/data
[ -d "$data" ] || { echo "render_suite.sh: $data is missing (the photographs and the lego set)" >&2; exit 1; }
# Photographs to cut textures from: buildings (Herz-Jesu), indoor scenes (Middlebury), a street
# (KITTI), outdoor video frames (DAVIS, VOT).
photos="$data/strecha_Herz-Jesu-P8/images,$data/middlebury2003_cones/im2.png"
photos+=",$data/middlebury2003_teddy/im2.png,$data/kitti_odometry_seq06_000-050/image_l/000000.png"
photos+=",$data/kitti_odometry_seq06_000-050/image_l/000030.png"
photos+=",$data/davis2016_car-shadow/JPEGImages/480p/car-shadow/00000.jpg,$data/vot_bag/00000001.jpg"
seed=${SEED:-1}
mkdir -p "$out"
for scene in "${scenes[@]}"; do
  args=()
  case "$scene" in
    street_drive_500|orbit_object) args=(--stereo-pairs 4) ;;
    lego_composite) args=(--nerf "$data/nerf_synthetic_lego") ;;
  esac
  file=scenes/$scene.json
  [ "$scene" = lego_composite ] && file=scenes/lego_background.json
  start=$(date +%s.%N)
  nice "$build_dir"/bin/comic_render "$file" --photos "$photos" --seed "$seed" \
    --depth-format pfm --noise 1.5 --shot-noise 0.2 --exposure-drift 0.1 -q \
    "${args[@]}" --output "$out/$scene"
  echo "render_suite.sh: $scene wall $(echo "$(date +%s.%N) - $start" | bc) s"
done
