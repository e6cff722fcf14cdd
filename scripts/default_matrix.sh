#!/usr/bin/env bash
# Runs comic_sfm with the given flags on every clip of ../shared/data that the README's users
# meet (video, ordered and unordered photo sets) and prints one table row per clip: registered
# frames in the largest model, models, interpolated frames, status, ATE and mean rotation error
# against the truth where the clip has it, wall and CPU seconds, CPU seconds per frame. Used for the default-choice tables of docs/matching.md.
#
#   scripts/default_matrix.sh OUT_DIR [comic_sfm flags...]     e.g. out/matrix/harris
#   COMIC_MATRIX_CLIPS="bag25 kitti06" scripts/default_matrix.sh out/m --detector comic
#
# Clips whose data is missing are skipped.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: default_matrix.sh OUT_DIR [comic_sfm flags...]}
shift
data=../shared/data
bin=${COMIC_BUILD_DIR:-build}/bin/comic_sfm
clips=${COMIC_MATRIX_CLIPS:-"bag25 bag50 bag196 car1 kitti06 lego herzjesu davis davis_masks temple dino48 dino363"}
mkdir -p "$out"

run_clip() {
  local name=$1 frames=$2
  shift 2
  [ -e "$frames" ] || { echo "$name: no data, skipped" >&2; return 0; }
  local dir="$out/$name"
  rm -rf "$dir"
  local start end
  start=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$out/$name.time" "$bin" "$frames" --output "$dir" "$@" \
    >"$out/$name.log" 2>&1 || true
  end=$(date +%s.%N)
  python3 - "$name" "$dir/report.json" "$out/$name.time" "$start" "$end" <<'PY'
import json, sys
name, report, timing, start, end = sys.argv[1:]
try:
    r = json.load(open(report))
except Exception:
    print(f"| {name} | no report | | | | | | | |")
    sys.exit(0)
user, system = (float(x) for x in open(timing).read().split()[-2:])
models = r.get("models", [])
ate = r.get("evaluation", {}).get("ate_rmse") if isinstance(r.get("evaluation"), dict) else None
def find(d, key):
    if isinstance(d, dict):
        for k, v in d.items():
            if k == key:
                return v
            f = find(v, key)
            if f is not None:
                return f
    return None
ate = find(r, "ate_rmse") if ate is None else ate
ate_s = f"{ate:.4g}" if isinstance(ate, (int, float)) else "-"
rot = find(r, "mean_rotation_error_deg")
rot_s = f"{rot:.3g}" if isinstance(rot, (int, float)) else "-"
n = r.get("frames")
interp = len((r.get("pose_sources") or {}).get("interpolated", []))
print(f"| {name} | {r.get('registered_frames')}/{n} | {len(models)} | {interp} | "
      f"{r.get('status')} | {ate_s} | {rot_s} | {float(end) - float(start):.0f} | "
      f"{user + system:.0f} | {(user + system) / max(n or 1, 1):.2f} |")
PY
}

echo "| clip | registered (largest) | models | interpolated | status | ATE | rotation error ° | wall s | CPU s | CPU s/frame |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for clip in $clips; do
  case $clip in
    bag25) run_clip bag25 $data/vot_bag --last 24 "$@" ;;
    bag50) run_clip bag50 $data/vot_bag --last 49 "$@" ;;
    bag196) run_clip bag196 $data/vot_bag "$@" ;;
    car1) run_clip car1 $data/vot2015_car1/imgs "$@" ;;
    kitti06) run_clip kitti06 $data/kitti_odometry_seq06_000-050/image_l \
      --gt $data/kitti_odometry_seq06_000-050/poses.txt "$@" ;;
    lego) run_clip lego $data/nerf_synthetic_lego/train \
      --gt $data/nerf_synthetic_lego/transforms_train.json "$@" ;;
    herzjesu) run_clip herzjesu $data/strecha_Herz-Jesu-P8/images \
      --gt $data/strecha_Herz-Jesu-P8/gt_dense_cameras "$@" ;;
    davis) run_clip davis $data/davis2016_car-shadow/JPEGImages/480p/car-shadow "$@" ;;
    davis_masks) run_clip davis_masks $data/davis2016_car-shadow/JPEGImages/480p/car-shadow \
      --masks $data/davis2016_car-shadow/Annotations/480p/car-shadow "$@" ;;
    temple) run_clip temple $data/middlebury_mview_templeSparseRing \
      --gt $data/middlebury_mview_templeSparseRing/templeSR_par.txt "$@" ;;
    dino48) run_clip dino48 $data/middlebury_mview_dino_ring48 \
      --gt $data/middlebury_mview_dino_ring48/dino_ring48_par.txt "$@" ;;
    dino363) run_clip dino363 $data/middlebury_mview_dino_full363/images \
      --gt $data/middlebury_mview_dino_full363/dino_full363_par.txt "$@" ;;
    *) echo "unknown clip $clip" >&2 ;;
  esac
done
