#!/usr/bin/env bash
# Install the Debian 12 packages rbc-ifem needs: deal.II 9.4 (with MPI,
# Trilinos, PETSc, METIS, ...), a compiler, CMake, MPI launchers, numdiff for
# the tests, strace for the fault test's injected kills, clang-format for the
# code style and python3 for the pages' generated tables
# (doc/scripts/tables.py). With --docs also what renders
# the documentation's figures (python3-matplotlib, a virtual X server and
# the DejaVu fonts) and ParaView's pvbatch with its Python modules for
# doc/scripts/paraview_lab_frame.py (paraview, python3-paraview; a build
# configured with them runs its test, label paraview); python3-paraview
# also carries VTK's Python modules (import vtk), which the render scripts
# use, and conflicts with Debian's python3-vtk9); and doxygen for the
# headers' reference (scripts/doxygen.sh). Uses sudo when not run as root.
set -euo pipefail

packages=(libdeal.ii-dev g++ cmake make openmpi-bin numdiff strace clang-format python3)
if [ "${1:-}" = "--docs" ]; then
  packages+=(python3-matplotlib xvfb xauth fonts-dejavu-core paraview python3-paraview doxygen)
fi

installed=$(dpkg-query -W -f='${Status}\n' "${packages[@]}" 2>/dev/null | grep -c "install ok installed" || true)
if [ "$installed" -ne "${#packages[@]}" ]; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${packages[@]}"
else
  echo "install-packages: ${packages[*]} already installed"
fi
