#!/usr/bin/env bash
# Usage: benchmarks/build_time.sh [REVISION...]
#
# Clean Release builds of the whole tree (library, programs, tests) with
# -j$(nproc), one revision after the other in one run, from clones of this
# repository in a scratch directory: the wall seconds and the number of
# translation units of each, as a Markdown table, whose rows are added to
# doc/results/benchmarks/build_time.csv (benchmarks/common.sh). Default
# revisions: the main before the architecture change (9f0856d) and HEAD.
set -euo pipefail
repository=$(cd "$(dirname "$0")/.." && pwd)
source "$repository/benchmarks/common.sh"
revisions=("$@")
[ ${#revisions[@]} -gt 0 ] || revisions=(9f0856d HEAD)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

results_table build_time revision "translation units" "clean build [s]"
for revision in "${revisions[@]}"; do
  rm -rf "$work/source" "$work/build"
  git clone -q "$repository" "$work/source"
  git -C "$work/source" checkout -q "$revision"
  cmake -S "$work/source" -B "$work/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  start=$(date +%s)
  cmake --build "$work/build" -j"$(nproc)" >"$work/build.log" 2>&1
  end=$(date +%s)
  units=$(grep -c 'Building CXX object' "$work/build.log")
  results_row "$(git -C "$work/source" rev-parse --short HEAD)" "$units" $((end - start))
done
