#!/usr/bin/env bash
# Build the Doxygen reference of the headers (include/rbc_ifem/), whose main
# page lists the classes by folder (doc/doxygen_mainpage.md), into
# build/doc/html/ (open build/doc/html/index.html). Needs doxygen
# (scripts/install-packages.sh --docs). Fails on a Doxygen error; its
# warnings are printed.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v doxygen >/dev/null ||
  { echo "doxygen.sh: doxygen is missing: scripts/install-packages.sh --docs" >&2; exit 1; }
mkdir -p build/doc
doxygen doc/Doxyfile
echo "doxygen: wrote build/doc/html/index.html"
