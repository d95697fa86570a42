#!/bin/bash
# The tests under AddressSanitizer, UndefinedBehaviorSanitizer and libstdc++'s
# bounds assertions: a read past a vector decides nothing visible in a normal
# build until the heap's garbage differs (stop 50: boundary_driven's
# quadrangulation read side[4] of a quad, and one face set came out different
# once in hundreds of runs). Not part of `make test` (the build alone takes
# about 25 minutes on two cores); run it with `make sanitize` after changes
# to the core.
#
# Builds a copy of the working tree (tracked and new files) in
# build-sanitize/src, so the normal build's module is left alone, then runs
# the C++ tests, the fingerprint cases and the Python tests given in
# SANITIZE_PYTEST (default: the face-set and boundary_driven tests; "all" for
# every Python test). Exits non-zero when a test fails or a sanitizer
# reported anything (the reports are in build-sanitize/logs).
#
# SANITIZE_KIND=thread builds with ThreadSanitizer instead (in
# build-sanitize-thread/) and runs the same tests with two threads
# (TESSELLA_THREADS=2): the metrics, the grid's trim cut, boundary_driven's
# cross field and the faces of a set run on every core.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
KIND=${SANITIZE_KIND:-address}
case "$KIND" in
  address)
    OUT=${SANITIZE_DIR:-$ROOT/build-sanitize}
    sanitizers=address,undefined
    flags="-fsanitize=address,undefined -fsanitize-recover=address,undefined -fno-omit-frame-pointer -D_GLIBCXX_ASSERTIONS"
    runtimes="libasan.so libubsan.so"
    ;;
  thread)
    OUT=${SANITIZE_DIR:-$ROOT/build-sanitize-thread}
    sanitizers=thread
    flags="-fsanitize=thread -fno-omit-frame-pointer"
    runtimes="libtsan.so"
    export TESSELLA_THREADS=2
    ;;
  *)
    echo "SANITIZE_KIND must be address or thread, not '$KIND'" >&2
    exit 2
    ;;
esac
SRC=$OUT/src
LOGS=$OUT/logs
JOBS=${JOBS:-2}
FREECAD_LIB=/usr/lib/freecad-python3/lib

mkdir -p "$SRC" "$LOGS"
rm -f "$LOGS"/*
(cd "$ROOT" && git ls-files -z --cached --others --exclude-standard |
  tar --null -T - -cf -) | tar -xf - -C "$SRC"

cmake -S "$SRC" -B "$SRC/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=$sanitizers" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=$sanitizers" >"$LOGS/../configure.log"
cmake --build "$SRC/build" -j"$JOBS" --target tessella_tests _core >"$LOGS/../build.log"

export ASAN_OPTIONS="detect_leaks=0:halt_on_error=0:log_path=$LOGS/asan"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=0:log_path=$LOGS/ubsan"
# OCCT's Boolean operations and TBB (FreeCAD's, in the tests' fixtures)
# are not instrumented: their own locks are invisible, so their accesses
# through the interceptors would be reported as races. Ours are instrumented.
export TSAN_OPTIONS="halt_on_error=0:ignore_noninstrumented_modules=1:log_path=$LOGS/tsan"
failed=0
echo "== C++ tests"
"$SRC/build/tessella_tests" --gtest_brief=1 || failed=1

# The module is loaded into Python, which is not built with a sanitizer: its
# runtime must come first.
preload=""
for lib in $runtimes; do preload="$preload${preload:+:}$(gcc -print-file-name=$lib)"; done
run_python() {
  (cd "$SRC" && LD_PRELOAD="$preload" PYTHONPATH="$FREECAD_LIB:$SRC" /usr/bin/python3 "$@")
}
echo "== fingerprint cases"
run_python bench/result_hashes.py --quiet --out "$OUT/result_hashes.json" || failed=1
echo "== Python tests"
case "${SANITIZE_PYTEST:-}" in
  "") tests=(tests/python/test_face_sets.py tests/python/test_boundary_driven.py) ;;
  all) tests=(tests/python) ;;
  *) read -r -a tests <<<"$SANITIZE_PYTEST" ;;
esac
run_python -m pytest -q -p no:cacheprovider "${tests[@]}" || failed=1

reports=$(find "$LOGS" -type f | wc -l)
if [ "$reports" -gt 0 ]; then
  echo "sanitizer reports ($reports files):"
  head -n 40 "$LOGS"/*
  failed=1
fi
[ "$failed" = 0 ] && echo "sanitize: no report, every test passed"
exit "$failed"
