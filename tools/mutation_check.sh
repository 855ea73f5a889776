#!/usr/bin/env bash
# Do the operator tests catch a broken operator? Puts one deliberate error at a time into a
# copy of the committed sources (git archive HEAD), builds the test suite there and runs the
# tests meant to catch that error: each must fail. Prints one line per error and exits
# non-zero if any error went unnoticed. Not part of ctest (a rebuild per error: minutes).
# Usage: tools/mutation_check.sh [-j N]
set -euo pipefail
jobs=2
if [[ "${1:-}" == "-j" ]]; then jobs="$2"; fi
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
git -C "$root" archive HEAD | tar -x -C "$work/"
cmake -S "$work" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DADRSPH_BUILD_BENCH=OFF \
  >"$work/configure.log"

# file | sed expression (the error) | gtest filter (the tests that must catch it) | what
mutations=(
  "src/schemes/continuity.hpp|s/return delta_h_c0_2 \* vol_j \* rho_ij \* lap_weight;/return delta_h_c0_2 * vol_j * rho_ij * lap_weight * T(0.5);/|Operators.DensityDiffusion*|eq. (8) density diffusion at half strength"
  "src/schemes/continuity.hpp|s/return rho_i \* vol_j \* u_dot_gradw;/return -rho_i * vol_j * u_dot_gradw;/|Operators.ContinuityOfLinear*|eq. (8) continuity with its sign flipped"
  "src/schemes/shifting.hpp|s/sx = -coefficient \* gx;/sx = coefficient * gx;/|Operators.Shifting*|eq. (10) shifting towards crowding (sign of x flipped)"
  "src/species/species_rate.hpp|s/diffusivity \* (vol_i + vol_j) \* lap_weight/diffusivity * vol_j * lap_weight/|Operators.DiffusionOperator*|eq. (12) species diffusion with V_j in place of V_i + V_j"
  "src/kernels/quintic_kernel.hpp|s/return dwdr \* r2 \* inv \* s;/using std::sqrt; return dwdr * sqrt(r2) * inv * s;/|FusedPass.*:Kernel.LaplacianWeight*|fused pass: Laplacian weight with r in place of r^2"
  "src/schemes/pair_records.hpp|s/lo = static_cast<float>(v - static_cast<double>(hi));/lo = 0.0f;/|FusedPass.*:PairRecords.*|force pass: differences of the state without the records' lo parts"
  "src/particles/particle_store.hpp|s/k == kInletByte) ? 1.0f/k != kWallByte) ? 1.0f/|PairRecords.*:Flow.*|diffusion mask taken from kind: the outflow buffer diffusing"
)

missed=0
for m in "${mutations[@]}"; do
  IFS='|' read -r file expr filter what <<<"$m"
  cp "$work/$file" "$work/$file.orig"
  sed -i "$expr" "$work/$file"
  if cmp -s "$work/$file" "$work/$file.orig"; then
    echo "NOT APPLIED  $what: the pattern no longer matches $file (update this script)"
    missed=1
    mv "$work/$file.orig" "$work/$file"
    continue
  fi
  if ! cmake --build "$work/build" -j "$jobs" --target adrsph_tests >"$work/build.log" 2>&1; then
    echo "BUILD FAILED $what (see the error below)"
    tail -20 "$work/build.log"
    missed=1
  elif OMP_NUM_THREADS=1 "$work/build/adrsph_tests" --gtest_filter="$filter" >"$work/test.log" 2>&1; then
    echo "MISSED       $what: $filter still passes"
    missed=1
  else
    failed=$(grep -oE '[0-9]+ FAILED TESTS?' "$work/test.log" | grep -oE '^[0-9]+' || echo "?")
    echo "caught       $what: $failed of the tests $filter fail"
    grep -m2 -E 'Expected|Which is|difference between|error:' "$work/test.log" |
      sed 's/^/               /' || true
  fi
  mv "$work/$file.orig" "$work/$file"
done
exit "$missed"
