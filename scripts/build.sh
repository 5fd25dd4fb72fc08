#!/usr/bin/env bash
# Configure (once) and build rbc-ifem and its tests in build/ (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
[ -f build/CMakeCache.txt ] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
