#!/usr/bin/env bash
# Builds the Debian package fleetmerge_<version>_<arch>.deb (CPack's DEB generator, Depends from
# dpkg-shlibdeps; cmake/FleetmergeDebianPackage.cmake) and prints its path.
#
# It reuses the Release build folder build/ (scripts/test.sh's or quickstart's), reconfigured for
# the package's prefix /usr (so that the library and CMake package go to /usr/lib/<multiarch>) and
# with the Python module on, and builds only the packaged targets: after scripts/test.sh they are
# up to date and the package costs a link or two and the compression.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh >&2
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}  # as scripts/build.sh: objects shared across folders
# CMAKE_SKIP_INSTALL_ALL_DEPENDENCY: cpack's install step would otherwise build every target of
# the folder (the test suite too); the packaged targets are built just below.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
  -DFLEETMERGE_BUILD_PYTHON=ON -DCMAKE_SKIP_INSTALL_ALL_DEPENDENCY=ON "${launcher[@]}" "$@" >&2
if ! grep -q '^FLEETMERGE_PYTHON_VERSION:INTERNAL=3\.' build/CMakeCache.txt; then
  echo "package.sh: the build has no Python module (pybind11-dev missing?): not packaging" >&2
  exit 1
fi
jobs=$(nproc 2>/dev/null || echo 2)
cmake --build build -j"$jobs" --target fleetmerge fleetmerge_lib fleetmerge_python >&2
out=build/package
rm -rf "$out/_CPack_Packages"
(cd build && cpack -G DEB -B "$PWD/package") >&2
version=$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' build/CMakeCache.txt)
deb=$out/fleetmerge_${version}_$(dpkg --print-architecture).deb
[ -f "$deb" ] || { echo "package.sh: cpack did not write $deb" >&2; exit 1; }
realpath "$deb"
