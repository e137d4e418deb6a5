#!/usr/bin/env bash
# Builds the tests and the libFuzzer harnesses with clang's AddressSanitizer
# and UndefinedBehaviorSanitizer in their own folder (build-asan/), then runs
# the tests. Any report fails the run: ASan stops at its first error, UBSan is
# made fatal (-fno-sanitize-recover=all), LeakSanitizer checks every exit.
#
#   scripts/sanitize.sh                  configure, build (-j$JOBS), run ctest
#   scripts/sanitize.sh --configure [ARGS]  configure only, ARGS to cmake
#   scripts/sanitize.sh --test           run ctest only, on the built folder
#
# Tests labelled `slow` are left out (see docs/testing.md for which and why)
# and not built. VIO_SANITIZE_LABELS overrides the ctest label filter, e.g.
#   VIO_SANITIZE_LABELS= scripts/sanitize.sh   (configure, build and run everything).
set -euo pipefail
cd "$(dirname "$0")/.."

build=${VIO_SANITIZE_BUILD:-build-asan}
labels=${VIO_SANITIZE_LABELS-slow}
# The suites a label filter leaves out are not built either (the sanitizer
# build is the longest part of CI): VIO_BUILD_SLOW_TESTS off when "slow" is
# filtered out.
slow_tests=ON
case ",$labels," in *,slow,*) slow_tests=OFF ;; esac
jobs=${JOBS:-2}
mode=${1:-all}
[ $# -gt 0 ] && shift

# Debian's Ceres is built without ASan; under ASan Eigen would switch to its
# own aligned allocator, so a matrix Ceres allocates and we free (or the
# reverse) would look like a heap overflow. Ceres' own setting says malloc is
# already aligned: use the same.
flags="-fsanitize=address,undefined -fno-sanitize-recover=all"
flags+=" -fno-omit-frame-pointer -DEIGEN_MALLOC_ALREADY_ALIGNED=1"
# Three UBSan checks are left out because AddressSanitizer (or Eigen's own
# assertion) already reports what they find, and they cost a third of this
# build's compile time (docs/testing.md): null (a null dereference is ASan's
# SEGV report), object-size (ASan's bounds checks are complete where this one
# sees only what the compiler can size) and alignment (no type punning in our
# code; a misaligned Eigen object trips Eigen's unaligned-array assertion,
# which is on in this build).
flags+=" -fno-sanitize=alignment,null,object-size"

configure() {
  cmake -S . -B "$build" \
    -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DCMAKE_CXX_FLAGS="$flags" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DVIO_BUILD_FUZZERS=ON -DVIO_BUILD_BENCHMARKS=OFF \
    -DVIO_BUILD_SLOW_TESTS=$slow_tests "$@"
}

run_tests() {
  local symbolizer
  symbolizer=$(command -v llvm-symbolizer-14 || command -v llvm-symbolizer || true)
  export ASAN_SYMBOLIZER_PATH=$symbolizer
  export ASAN_OPTIONS=detect_leaks=1:check_initialization_order=1:strict_init_order=1:detect_stack_use_after_return=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  if [ "$slow_tests" = ON ] &&
     grep -q '^VIO_BUILD_SLOW_TESTS:BOOL=OFF' "$build/CMakeCache.txt" 2>/dev/null; then
    echo "sanitize.sh: $build was configured without the slow suites;" \
         "run without --test to configure and build them" >&2
    exit 1
  fi
  ctest --test-dir "$build" --output-on-failure -j"$jobs" \
    ${labels:+-LE "$labels"}
}

case "$mode" in
  --configure) configure "$@" ;;
  --test) run_tests ;;
  all)
    configure
    cmake --build "$build" -j"$jobs"
    run_tests
    ;;
  *) echo "sanitize.sh: unknown option $mode" >&2; exit 1 ;;
esac
