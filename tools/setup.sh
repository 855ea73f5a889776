#!/usr/bin/env bash
# Installs the Debian 12 packages adrsph needs (only those missing), then configures and
# builds into build/ (Release). Run as root, or as a user with sudo.
#   tools/setup.sh                   # install + build
#   ADRSPH_WERROR=ON tools/setup.sh  # warnings as errors (what tools/test.sh and CI use)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config            # compiler (GCC, with OpenMP), CMake
  libeigen3-dev libhdf5-dev                   # linear algebra, field output
  libtomlplusplus-dev libcli11-dev            # case files, command line
  nlohmann-json3-dev                          # run.json
  libgtest-dev libgmock-dev libbenchmark-dev  # tests, benchmarks
  valgrind                                    # perf regression guard (perf/guard.sh)
  python3 python3-matplotlib python3-h5py     # tools/*.py (plots)
)

tools/install_packages.sh setup "${packages[@]}"

# ADRSPH_WERROR is passed only when set, so that a build dir keeps its setting (no full rebuild
# when the first README command follows the second).
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release ${ADRSPH_WERROR:+-DADRSPH_WERROR="$ADRSPH_WERROR"}
cmake --build build -j2
