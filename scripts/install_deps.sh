#!/usr/bin/env bash
# Installs, with apt-get, only the Debian packages comic-sfm needs that are missing.
# Idempotent and quiet when everything is present. Run as root (or with sudo available).
#
#   scripts/install_deps.sh            # install what is missing
#   scripts/install_deps.sh --check    # list what is missing, install nothing (exit 1 if any)
set -euo pipefail

PACKAGES=(
  g++            # C++17 compiler
  make
  cmake
  pkg-config
  libopencv-dev  # core, imgproc, imgcodecs, videoio, video, features2d, calib3d
  libceres-dev   # bundle adjustment
  libeigen3-dev
  libsqlite3-dev # COLMAP database
  nlohmann-json3-dev  # JSON reports
  libgtest-dev   # GoogleTest (CMake finds GTest::gtest_main)
  colmap         # the real COLMAP 3.8 binary, used by tests and --compare-colmap
  python3-dev    # the Python module comic (python/): headers for the interpreter
  pybind11-dev   # its C++/Python bindings (CMake finds pybind11)
  python3-pybind11
  python3-numpy  # its arrays
  python3-pytest # its test suite (ctest python/pytest)
  python3-pip    # its wheel (pyproject.toml), built offline with setuptools and wheel (ctest python/wheel)
  python3-setuptools
  python3-wheel
  python3-venv   # the README's `python3 -m venv --system-site-packages .venv && .venv/bin/pip install ...`
  python3-dask   # comic.distributed: chunks of a run as tasks on a Dask cluster (docs/distributed.md)
  python3-distributed  # its scheduler and workers (LocalCluster on one machine)
  clang          # libFuzzer targets in fuzz/ (scripts/fuzz.sh)
  libfuzzer-14-dev
  libjs-three    # three.js, inlined into report.html's 3-D view (io/report/html_page.h)
  chromium       # headless browser: the tests render report.html and check it draws
)

missing=()
for pkg in "${PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$pkg" 2>/dev/null || true)
  [ "$status" = "installed" ] || missing+=("$pkg")
done

if [ "${#missing[@]}" -eq 0 ]; then
  exit 0
fi

if [ "${1:-}" = "--check" ]; then
  echo "missing: ${missing[*]}"
  exit 1
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    SUDO="sudo"
  else
    echo "install_deps.sh: must run as root to install: ${missing[*]}" >&2
    exit 1
  fi
fi

echo "install_deps.sh: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install_deps.sh: done"
