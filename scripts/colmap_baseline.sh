#!/usr/bin/env bash
# Runs COLMAP's own pipeline with its defaults on a folder of frames, for the side-by-side tables of
# docs/results.md and docs/matching.md: SIFT extraction (one shared camera, COLMAP's default
# SIMPLE_RADIAL), then the sequential matcher for a video (each frame against the next 10, plus
# quadratic overlap) or the exhaustive matcher for an image set, then the incremental mapper.
# Prints each stage's wall and CPU seconds and the registered images per model; writes every model
# as text under OUT/sparse/N, ready for scripts/compare_models.py.
#
#   scripts/colmap_baseline.sh FRAMES_DIR OUT_DIR [sequential|exhaustive] [THREADS]
#
# THREADS (default 1) is given to every stage; compare CPU seconds with comic_sfm's at the same
# thread count.
set -euo pipefail
frames=${1:?usage: colmap_baseline.sh FRAMES_DIR OUT_DIR [sequential|exhaustive] [THREADS]}
out=${2:?usage: colmap_baseline.sh FRAMES_DIR OUT_DIR [sequential|exhaustive] [THREADS]}
matching=${3:-sequential}
threads=${4:-1}
case "$matching" in sequential | exhaustive) ;; *)
  echo "colmap_baseline.sh: matching must be sequential or exhaustive, not '$matching'" >&2
  exit 2
  ;;
esac
[ -d "$frames" ] || { echo "colmap_baseline.sh: no such folder: $frames" >&2; exit 2; }
command -v colmap >/dev/null || { echo "colmap_baseline.sh: colmap is not installed" >&2; exit 2; }
[ -e "$out" ] && { echo "colmap_baseline.sh: $out exists; give a new folder" >&2; exit 2; }
mkdir -p "$out/sparse"
db="$out/database.db"

stage() {
  local name=$1
  shift
  local start end
  start=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$out/$name.time" colmap "$@" >"$out/$name.log" 2>&1
  end=$(date +%s.%N)
  read -r user sys <"$out/$name.time"
  awk -v n="$name" -v w="$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')" \
    -v c="$(awk -v a="$user" -v b="$sys" 'BEGIN { print a + b }')" \
    'BEGIN { printf "colmap %s: wall %.0f s, CPU %.0f s\n", n, w, c }'
}

stage feature_extractor feature_extractor --database_path "$db" --image_path "$frames" \
  --ImageReader.single_camera 1 --SiftExtraction.use_gpu 0 --SiftExtraction.num_threads "$threads"
stage "${matching}_matcher" "${matching}_matcher" --database_path "$db" \
  --SiftMatching.use_gpu 0 --SiftMatching.num_threads "$threads"
stage mapper mapper --database_path "$db" --image_path "$frames" --output_path "$out/sparse" \
  --Mapper.num_threads "$threads"

for model in "$out"/sparse/*/; do
  colmap model_converter --input_path "$model" --output_path "$model" --output_type TXT \
    >/dev/null 2>&1
  registered=$(grep -v '^#' "$model/images.txt" | awk 'NR % 2 == 1' | wc -l)
  echo "colmap model $(basename "$model"): $registered images registered"
done
