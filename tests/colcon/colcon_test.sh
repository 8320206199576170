#!/usr/bin/env bash
# fleetmerge in a colcon workspace (a CI stage after scripts/test.sh): `colcon build` builds the
# repository's package.xml package and a second package, tests/colcon/fleetmerge_consumer, that
# finds it with find_package(fleetmerge); the consumer then runs from the workspace's install.
#
# Cheap through ccache: the workspace is laid out so that fleetmerge's compile commands are the
# ones scripts/test.sh's build ran (same flags, same relative paths), so its objects are cache
# hits. ccache rewrites paths under CCACHE_BASEDIR relative to the compiler's folder; the build
# folder of fleetmerge is a child of its source folder, as build/ is of the repository: the
# workspace's src/fleetmerge is a folder of links to the repository's entries, and build/fleetmerge
# links to src/fleetmerge/build (CMake builds in the resolved folder).
set -euo pipefail
cd "$(dirname "$0")/../.."
repo=$PWD
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v colcon >/dev/null || fail "colcon not found (scripts/install_deps.sh installs it)"

ws=$(mktemp -d /tmp/fleetmerge_colcon.XXXXXX)
trap 'rm -rf "$ws"' EXIT
mkdir -p "$ws/src/fleetmerge" "$ws/build"
for entry in "$repo"/* "$repo"/.clang-format; do
  case $(basename "$entry") in build* | out) continue ;; esac
  ln -s "$entry" "$ws/src/fleetmerge/"
done
ln -s "$repo/tests/colcon/fleetmerge_consumer" "$ws/src/fleetmerge_consumer"
mkdir "$ws/src/fleetmerge/build"
ln -s "$ws/src/fleetmerge/build" "$ws/build/fleetmerge"

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR=$ws
ccache_counts() {  # hits and misses so far (the cache is shared: differences only)
  command -v ccache >/dev/null || { echo "0 0"; return; }
  ccache --print-stats | awk '/^(direct|preprocessed)_cache_hit/ {h += $2} /^cache_miss/ {m += $2}
                              END {print h + 0, m + 0}'
}
read -r hits0 misses0 < <(ccache_counts)
start=$SECONDS
(cd "$ws" && colcon build --cmake-args -DCMAKE_BUILD_TYPE=Release \
  -DFLEETMERGE_BUILD_TESTS=OFF -DFLEETMERGE_BUILD_BENCHMARKS=OFF "${launcher[@]}") \
  > "$ws/colcon_build.log" 2>&1 || { tail -n 60 "$ws/colcon_build.log"; fail "colcon build"; }
echo "colcon build of fleetmerge and fleetmerge_consumer: $((SECONDS - start)) s"
read -r hits1 misses1 < <(ccache_counts)
echo "ccache: $((hits1 - hits0)) hits, $((misses1 - misses0)) misses (other builds on the machine count too)"

# The workspace's environment, as a user sources it: the command and the consumer on PATH, the
# library on LD_LIBRARY_PATH. setup.bash reads unset variables: no `set -u` while sourcing.
set +u
# shellcheck disable=SC1091
source "$ws/install/setup.bash"
set -u
[ "$(command -v fleetmerge)" = "$ws/install/fleetmerge/bin/fleetmerge" ] ||
  fail "fleetmerge on PATH is $(command -v fleetmerge)"
version=$(fleetmerge --version | cut -d' ' -f2)
read -r x y yaw omega header_version library_version < <(fleetmerge_consumer)
echo "fleetmerge_consumer: $x $y $yaw $omega, header $header_version, library $library_version"
[ "$header_version" = "$version" ] && [ "$library_version" = "$version" ] ||
  fail "versions: command $version, header $header_version, library $library_version"
/usr/bin/python3 -c "import sys; x, y, yaw, o = map(float, sys.argv[1:]); \
assert abs(x - 1.0) < 0.05 and abs(y - 0.5) < 0.05 and abs(yaw) < 0.01 and o > 0.9, sys.argv" \
  "$x" "$y" "$yaw" "$omega" || fail "the consumer's pair is not (1.0, 0.5, 0)"
echo "colcon_test: all checks passed"
