#!/usr/bin/env bash
# The README's second command: build if needed and run the test suite.
# Extra arguments go to ctest, e.g. `scripts/test.sh -L mpi` or `-R layout`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
