#!/usr/bin/env bash
# libFuzzer targets of fuzz/ (issue 19), built with clang and -fsanitize=fuzzer,address,undefined
# into build-fuzz/ (or $COMIC_FUZZ_BUILD_DIR).
#
#   scripts/fuzz.sh TARGET SECONDS    # fuzz one target, e.g. fuzz_regions 600
#   scripts/fuzz.sh --all SECONDS     # every target in turn (CI: 20 s each)
#   scripts/fuzz.sh --list            # the targets
#   COMIC_FUZZ_SEED=N scripts/fuzz.sh ...   # another seed than 1 (long runs: vary it)
#
# Seeds come from fuzz/corpus/TARGET/ (made from the bundled example); inputs that reach new code
# are kept in build-fuzz/corpus/TARGET/, crashes in build-fuzz/artifacts/TARGET/ (the script
# fails then, and prints how to replay one: build-fuzz/fuzz/TARGET ARTIFACT).
set -euo pipefail
cd "$(dirname "$0")/.."
targets=(fuzz_image_detectors fuzz_ground_truth fuzz_regions fuzz_colmap_database
         fuzz_colmap_text_model fuzz_calibration_values fuzz_scene fuzz_exif_focal)
if [ "${1:-}" = "--list" ]; then
  printf '%s\n' "${targets[@]}"
  exit 0
fi
if [ $# -ne 2 ] || ! [[ "$2" =~ ^[0-9]+$ ]] || [ "$2" -lt 1 ]; then
  echo "usage: scripts/fuzz.sh TARGET|--all SECONDS   (targets: ${targets[*]})" >&2
  exit 2
fi
if [ "$1" = "--all" ]; then
  selected=("${targets[@]}")
else
  printf '%s\n' "${targets[@]}" | grep -qx "$1" || {
    echo "fuzz.sh: unknown target '$1' (targets: ${targets[*]})" >&2
    exit 2
  }
  selected=("$1")
fi
seconds=$2
if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz.sh: clang++ is missing (scripts/install_deps.sh installs clang and libfuzzer-14-dev)" >&2
  exit 1
fi
build_dir=${COMIC_FUZZ_BUILD_DIR:-build-fuzz}
# -O1 -g1 as the sanitizer build (scripts/sanitize.sh): compiles far faster than -O2 -g.
cmake -S . -B "$build_dir" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCOMIC_BUILD_FUZZERS=ON \
  -DCOMIC_BUILD_TESTS=OFF >/dev/null
cmake --build "$build_dir" -j "$(nproc)" --target "${selected[@]}"

export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export LSAN_OPTIONS=suppressions=$PWD/scripts/sanitizers/lsan.supp:print_suppressions=0
for target in "${selected[@]}"; do
  corpus="$build_dir/corpus/$target"
  artifacts="$build_dir/artifacts/$target"
  mkdir -p "$corpus" "$artifacts"
  log="$build_dir/$target.log"
  # -rss_limit_mb: a single input may not take more than 2.5 GB; -timeout: nor 25 s.
  # -seed: a fixed seed (COMIC_FUZZ_SEED, default 1) makes a CI run repeatable: the inputs it
  # tries are the same on every machine, only how far it gets in SECONDS differs.
  if ! "$build_dir/fuzz/$target" -max_total_time="$seconds" -seed="${COMIC_FUZZ_SEED:-1}" \
      -rss_limit_mb=2560 -timeout=25 \
      -print_final_stats=1 -artifact_prefix="$artifacts/" "$corpus" "fuzz/corpus/$target" \
      >"$log" 2>&1; then
    tail -n 40 "$log" >&2
    echo "fuzz.sh: $target found a crash: replay with $build_dir/fuzz/$target $artifacts/<file>" >&2
    exit 1
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  echo "fuzz.sh: $target: ${runs:-?} inputs in ${seconds} s, no crash (corpus: $(ls "$corpus" | wc -l) files)"
done
