#!/usr/bin/env bash
# The boundary question in SfM on the rendered suite, in one command (docs/rendered_benchmark.md):
#   scripts/rendered_benchmark.sh [SUITE] [OUT]        (defaults out/suite, out/rendered_benchmark)
# Renders what SUITE lacks (scripts/render_suite.sh), then for every detector and comic+hessian:
#   comic_render_eval on the street drive (frames 0..STREET_LAST), the orbit (every
#     ORBIT_STRIDE-th frame), the handheld walk and the lego composite   -> OUT/<sequence>/
#   comic_stereo_eval on the rendered stereo pairs and on Middlebury's   -> OUT/stereo_*/
# Environment: DETECTORS (comma list), STREET_LAST (199), ORBIT_STRIDE (2), WALK_STRIDE (1),
# THREADS (1). Everything runs under nice; numbers change as the tracker and mapper do, so rerun
# this and update the docs page with what it prints.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${COMIC_BUILD_DIR:-build}
suite=${1:-out/suite}
out=${2:-out/rendered_benchmark}
detectors=${DETECTORS:-comic,comic-paper,harris,hessian,mser,fast,comic+hessian}
threads=${THREADS:-1}
data=../shared/data
mkdir -p "$out"
for scene in street_drive_500 orbit_object handheld_walk lego_composite; do
  [ -f "$suite/$scene/scene.json" ] || scripts/render_suite.sh "$suite" "$scene"
done

evaluate() {  # name, folder, extra options...
  local name=$1 folder=$2
  shift 2
  local start
  start=$(date +%s)
  nice "$build_dir"/bin/comic_render_eval "$folder" --detectors "$detectors" --threads "$threads" \
    -q "$@" --output "$out/$name" > "$out/$name.log"
  echo "rendered_benchmark.sh: $name done in $(( $(date +%s) - start )) s"
  cat "$out/$name/boundary_benchmark.md"
}
evaluate street "$suite/street_drive_500" --last "${STREET_LAST:-199}"
evaluate orbit "$suite/orbit_object" --stride "${ORBIT_STRIDE:-2}"
evaluate walk "$suite/handheld_walk" --stride "${WALK_STRIDE:-1}"
evaluate lego "$suite/lego_composite"

# The stereo protocol (paper §5.2.2) on rendered pairs with exact disparity, and on Middlebury's.
rendered_pairs=$(ls -d "$suite"/street_drive_500/stereo/* "$suite"/orbit_object/stereo/* | paste -sd,)
nice "$build_dir"/bin/comic_stereo_eval --middlebury "$rendered_pairs" --threads "$threads" -q \
  --output "$out/stereo_rendered"
nice "$build_dir"/bin/comic_stereo_eval \
  --middlebury "$data/middlebury2001_tsukuba,$data/middlebury2003_cones,$data/middlebury2003_teddy" \
  --threads "$threads" -q --output "$out/stereo_middlebury"
echo "rendered_benchmark.sh: stereo tables in $out/stereo_rendered/ and $out/stereo_middlebury/"
