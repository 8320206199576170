#!/usr/bin/env bash
# Installs fleetmerge's dependencies from Debian 12's packages.
#   install_deps.sh         everything: build, tests, fuzzers, browser test, packaging, colcon
#   install_deps.sh --cli   only what building the `fleetmerge` command needs (scripts/quickstart.sh)
# Idempotent: packages already present are left as they are. Needs root (or sudo).
set -euo pipefail

# The command (cli/) and the libraries it links: configure with tests, benchmarks and the Python
# module off, `--target fleetmerge`. OpenCV core and imgproc only (imgcodecs pulls GDAL).
cli_packages=(
  build-essential cmake pkg-config
  libeigen3-dev libceres-dev libopencv-core-dev libopencv-imgproc-dev
  liboctomap-dev libyaml-cpp-dev libspng-dev zlib1g-dev nlohmann-json3-dev libcli11-dev
  libxxhash-dev  # header-only here: the re-run cache's content hash (io/content_hash.hpp)
  libbz2-dev liblz4-dev libzstd-dev libsqlite3-dev  # bag readers (rosbag/: ROS 1, MCAP, db3)
)
packages=(
  "${cli_packages[@]}"
  git ccache
  libopencv-imgcodecs-dev  # three tests decode PNGs with OpenCV, independently of ours
  libgtest-dev libgmock-dev libbenchmark-dev
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module and its tests
  python3-rosbag python3-nav-msgs python3-geometry-msgs python3-std-msgs  # ROS 1 bag fixtures
  zstd  # tests/data/bags/make_bags.py --message-zstd (rosbag2 MESSAGE compression fixtures)
  clang libclang-rt-14-dev  # scripts/fuzz.sh: clang 14 and its libFuzzer/sanitizer runtimes
  # tests/browser: report.html opened in headless Chromium, driven by a Node script (no npm
  # package); a font so that the page's text renders in its screenshots.
  chromium nodejs fonts-dejavu-core
  python3-roslaunch  # tests/rosbag: transforms.launch loaded by ROS 1's own roslaunch
  dpkg-dev  # scripts/package.sh: dpkg-shlibdeps computes the .deb's Depends
  # tests/colcon: colcon with its CMake and package.xml (colcon-ros) support and setup.bash
  colcon python3-colcon-cmake python3-colcon-ros python3-colcon-bash
  python3-colcon-library-path python3-colcon-parallel-executor
)
with_npm=1  # the tests' npm packages; the command needs none
case "${1:-}" in
  --cli) packages=("${cli_packages[@]}") with_npm=0 ;;
  "") ;;
  *) echo "usage: install_deps.sh [--cli]" >&2; exit 2 ;;
esac

# tests/rosbag: the npm packages (package-lock.json) that read the result set's merged_bag/.
# npm comes with Debian's nodejs as its own package, or with nodejs from elsewhere (which then
# conflicts with Debian's npm): installed only when missing.
install_npm_packages() {
  [ "$with_npm" -eq 1 ] || return 0
  local here sudo=""
  here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../tests/rosbag" && pwd)"
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  command -v npm >/dev/null || $sudo apt-get install -y -qq --no-install-recommends npm
  if [ ! -f "$here/node_modules/.package-lock.json" ] ||
    [ "$here/package-lock.json" -nt "$here/node_modules/.package-lock.json" ]; then
    echo "install_deps: npm ci in tests/rosbag"
    (cd "$here" && npm ci --no-audit --no-fund --loglevel=error)
  fi
}

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages already installed"
  install_npm_packages
  exit 0
fi

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
install_npm_packages
