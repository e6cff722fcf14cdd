#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test with CTest; then the sanitizer run
# (scripts/sanitize.sh: unit tests and the bundled example built with -fsanitize=address,undefined)
# and a short run of every fuzz target (scripts/fuzz.sh, skipped where clang is missing).
# COMIC_SKIP_SANITIZE=1 / COMIC_SKIP_FUZZ=1 leave those out (e.g. while iterating).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build_dir=${COMIC_BUILD_DIR:-build}
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)"
if [ "${COMIC_SKIP_SANITIZE:-0}" != 1 ]; then
  scripts/sanitize.sh
fi
if [ "${COMIC_SKIP_FUZZ:-0}" != 1 ]; then
  scripts/fuzz.sh --all "${COMIC_FUZZ_SECONDS:-20}"
fi
