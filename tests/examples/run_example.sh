#!/usr/bin/env bash
# Usage: run_example.sh PREFIX EXAMPLE_DIR [ARGUMENT...] -- CHECK...
#
# Builds a tutorial program as a user would, against the rbc-ifem installed
# in PREFIX (cmake -S EXAMPLE_DIR -DCMAKE_PREFIX_PATH=PREFIX, outside our
# tree), runs it with the ARGUMENTs in its build directory, and checks its
# printed numbers. Each CHECK is "TEXT|VALUE|TOLERANCE": the number that
# follows TEXT on the first line containing it must lie within the relative
# TOLERANCE of VALUE.
set -u
prefix=$1
example=$2
shift 2
arguments=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do arguments+=("$1"); shift; done
shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
name=$(basename "$example")

cmake -S "$example" -B "$work/build" -DCMAKE_PREFIX_PATH="$prefix" >"$work/configure.log" 2>&1 \
  || { cat "$work/configure.log"; echo "FAILED: configuring $name against $prefix"; exit 1; }
cmake --build "$work/build" -j2 >"$work/build.log" 2>&1 \
  || { cat "$work/build.log"; echo "FAILED: building $name"; exit 1; }
cd "$work/build" || exit 1
"./$name" "${arguments[@]}" >run.log 2>&1
status=$?
cat run.log
[ $status -eq 0 ] || { echo "FAILED: $name exits with status $status"; exit 1; }

failed=0
for check in "$@"; do
  IFS='|' read -r text expected tolerance <<<"$check"
  value=$(grep -m1 -F -- "$text" run.log | sed "s|.*$text *\([-+0-9.eE]*\).*|\1|")
  if awk -v v="$value" -v e="$expected" -v t="$tolerance" \
       'BEGIN { d = v - e; if (d < 0) d = -d; exit !(v != "" && d <= t * (e < 0 ? -e : e)) }'; then
    echo "ok: $name prints '$text $value', within $tolerance of $expected"
  else
    echo "FAILED: $name prints '$text ${value:-nothing}', not within $tolerance of $expected"
    failed=1
  fi
done
exit $failed
