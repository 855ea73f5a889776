#!/usr/bin/env bash
# The sanitizer and fuzz checks of docs/robustness.md; CI runs them after tools/test.sh.
#   tools/sanitizers.sh              # all three, in this order
#   tools/sanitizers.sh asan         # the test suite under AddressSanitizer + UBSan (GCC)
#   tools/sanitizers.sh tsan         # the OpenMP tests under ThreadSanitizer (clang, libomp, Archer)
#   tools/sanitizers.sh fuzz [SECONDS]  # the case-loader fuzz target (clang, libFuzzer), 60 s
# Build directories: build-asan, build-tsan, build-fuzz. Installs what is missing (as root or
# with sudo), like tools/setup.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(clang libclang-rt-14-dev libomp-14-dev)
tools/install_packages.sh sanitizers "${packages[@]}"

# -O1: sanitizer reports keep their stack traces, and the suite stays quick.
common=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g"
        -DADRSPH_BUILD_BENCH=OFF)
export OMP_WAIT_POLICY=passive

asan() {
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer: the test suite"
  cmake -S . -B build-asan "${common[@]}" -DADRSPH_SANITIZE=address,undefined -DADRSPH_WERROR=ON
  cmake --build build-asan -j2
  # The perf guard runs valgrind, which cannot run a sanitized binary.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan -LE perf --output-on-failure -j2
}

tsan() {
  echo "== ThreadSanitizer: the OpenMP passes on small cases"
  local archer=/usr/lib/llvm-14/lib/libarcher.so
  [[ -f $archer ]] || { echo "sanitizers: $archer missing (libomp-14-dev)" >&2; exit 1; }
  cmake -S . -B build-tsan "${common[@]}" -DADRSPH_SANITIZE=thread \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++
  cmake --build build-tsan -j2 --target adrsph_tests
  # Archer tells TSan about OpenMP's barriers and tasks; without it every pass is reported.
  OMP_NUM_THREADS=2 OMP_TOOL_LIBRARIES=$archer \
    TSAN_OPTIONS="halt_on_error=1 ignore_noninstrumented_modules=1" \
    build-tsan/adrsph_tests --gtest_filter="$TSAN_TESTS"
}
# The tests that run the OpenMP neighbour passes, the boundary update and a few steps.
TSAN_TESTS='FusedPass.*:Operators.*:Neighbours.*:Flow.*:Species.*:Robustness.*'

fuzz() {
  local seconds=${1:-60}
  echo "== libFuzzer: the case loader and --set parser, ${seconds} s"
  cmake -S . -B build-fuzz -DADRSPH_FUZZ=ON -DADRSPH_BUILD_TESTS=OFF -DADRSPH_BUILD_BENCH=OFF \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++
  cmake --build build-fuzz -j2 --target adrsph_fuzz_case
  # New inputs go to a scratch copy of the corpus: the committed seeds stay as they are.
  local corpus
  corpus=$(mktemp -d)
  trap 'rm -rf "$corpus"' RETURN
  cp tests/fuzz/corpus/* cases/*.toml "$corpus"/
  build-fuzz/adrsph_fuzz_case -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 "$corpus"
}

case "${1:-all}" in
  asan) asan ;;
  tsan) tsan ;;
  fuzz) fuzz "${2:-60}" ;;
  all) asan; tsan; fuzz 60 ;;
  *) echo "usage: tools/sanitizers.sh [asan|tsan|fuzz [SECONDS]|all]" >&2; exit 2 ;;
esac
