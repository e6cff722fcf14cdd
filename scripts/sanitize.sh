#!/usr/bin/env bash
# The sanitizer run of CI (issue 19): builds comic-sfm with -fsanitize=address,undefined into a
# separate folder (build-sanitize/, or $COMIC_SANITIZE_BUILD_DIR) and runs, through it, the unit
# tests (every ctest test except the end-to-end apps/ ones, which run the same code through the
# apps and are not even built here, see tests/CMakeLists.txt) and the bundled example. Any AddressSanitizer or LeakSanitizer report, and any undefined
# behaviour (-fno-sanitize-recover=undefined), fails the run. Third-party leaks are suppressed by
# name in scripts/sanitizers/lsan.supp.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${COMIC_SANITIZE_BUILD_DIR:-build-sanitize}
start=$(date +%s)
# Not the Python module (an ASan runtime cannot be loaded into an unsanitized interpreter without
# LD_PRELOAD, and the interpreter's own allocations then read as leaks) nor the installed-package
# consumer (a plain build of its own): both run in the normal build's ctest; the C++ they call is
# what the sanitized unit tests cover.
# -O1 -g1 (line tables: what a sanitizer's stack trace needs), not RelWithDebInfo's -O2 -g: the
# sanitized build compiles 2-3x faster (sfm/bundle_adjuster.cc: 155 s -> 51 s with gcc), the
# tests run somewhat slower, the stage as a whole is shorter.
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCOMIC_SANITIZE=ON \
  -DCOMIC_BUILD_PYTHON=OFF >/dev/null
cmake --build "$build_dir" -j "$(nproc)"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:halt_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
# The tests on ../shared/data (whole reconstructions of real clips) skip here: the Release run
# has just run them, and the code they reach is the code the synthetic tests reach.
export COMIC_TEST_WITHOUT_SHARED_DATA=1
export LSAN_OPTIONS=suppressions=$PWD/scripts/sanitizers/lsan.supp:print_suppressions=0

log=$(mktemp)
trap 'rm -f "$log"' EXIT
# Whole reconstructions that take over 30 s sanitized run in the Release stage only (listed,
# with the reason, in scripts/sanitizers/slow_tests.txt).
slow=$(grep -v '^#' scripts/sanitizers/slow_tests.txt | grep . | paste -sd'|')
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" \
  -E "^(apps|layout|package|python)/|_browser\.|${slow}" | tee "$log"
tests_run=$(sed -n 's/.*tests failed out of \([0-9]*\).*/\1/p' "$log" | tail -1)

example_out=$(mktemp -d)
trap 'rm -f "$log"; rm -rf "$example_out"' EXIT
"$build_dir"/bin/comic_sfm examples/data/kitti06_000-011/image_l \
  --gt examples/data/kitti06_000-011/poses.txt --compare --quiet --output "$example_out" >/dev/null
test -f "$example_out/compare.md"
echo "sanitizer run (address, undefined, leak): ${tests_run:-0} tests and the bundled example" \
  "(comic_sfm --compare, every detector) passed in $(($(date +%s) - start)) s"
