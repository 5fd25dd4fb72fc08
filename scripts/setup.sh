#!/usr/bin/env bash
# The README's first command: install the Debian packages, build, and run
# the default experiment prm/default.prm (its files go to output/default/,
# replacing those of an earlier run of this script: --overwrite).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-packages.sh
scripts/build.sh
build/rbc-ifem prm/default.prm --overwrite
