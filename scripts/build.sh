#!/usr/bin/env bash
# Installs what is missing (scripts/install_deps.sh), then configures and builds comic-sfm in
# Release mode into build/ (or $COMIC_BUILD_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
build_dir=${COMIC_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
