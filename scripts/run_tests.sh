#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test with CTest; then the sanitizer run
# (scripts/sanitize.sh: unit tests and the bundled example built with -fsanitize=address,undefined)
# and a short run of every fuzz target (scripts/fuzz.sh, skipped where clang is missing).
# COMIC_SKIP_SANITIZE=1 / COMIC_SKIP_FUZZ=1 leave those out (e.g. while iterating).
set -euo pipefail
cd "$(dirname "$0")/.."
# Each stage's wall time is printed at the end: CI has a 90-minute limit on a 2-core machine.
stage_start=$(date +%s)
stage_times=()
end_stage() {
  stage_times+=("$1 $(($(date +%s) - stage_start)) s")
  stage_start=$(date +%s)
}
scripts/build.sh
end_stage build
build_dir=${COMIC_BUILD_DIR:-build}
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)"
end_stage tests
if [ "${COMIC_SKIP_SANITIZE:-0}" != 1 ]; then
  scripts/sanitize.sh
  end_stage sanitizers
fi
if [ "${COMIC_SKIP_FUZZ:-0}" != 1 ]; then
  scripts/fuzz.sh --all "${COMIC_FUZZ_SECONDS:-20}"
  end_stage fuzz
fi
echo "run_tests.sh stages: $(IFS=,; echo "${stage_times[*]}" | sed 's/,/, /g')"
