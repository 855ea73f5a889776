#!/usr/bin/env bash
# Installs what is missing, builds with warnings as errors, and runs the whole test suite.
# This is README's second command; CI (.ci/run) runs it, then tools/sanitizers.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
ADRSPH_WERROR=ON tools/setup.sh
ctest --test-dir build --output-on-failure -j2
