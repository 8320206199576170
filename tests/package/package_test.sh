#!/usr/bin/env bash
# The Debian package as a user gets it (a CI stage after scripts/test.sh, whose build/ it reuses):
# scripts/package.sh builds it, `apt-get install ./fleetmerge_*.deb` installs it with its
# Depends, then the installed command, Python module and CMake package are used the way a user
# would (no PYTHONPATH, no CMAKE_PREFIX_PATH), and `apt-get purge` must leave no file of it behind.
# Needs root (apt-get); installs into /usr and removes itself at the end.
set -euo pipefail
cd "$(dirname "$0")/../.."
source=$PWD
fail() { echo "FAIL: $*" >&2; exit 1; }

deb=$(bash scripts/package.sh | tail -n 1)
echo "package: $deb ($(du -h "$deb" | cut -f1))"
tmp=$(mktemp -d)
export DEBIAN_FRONTEND=noninteractive
remove_package() { dpkg-query -W fleetmerge >/dev/null 2>&1 && apt-get purge -y -qq fleetmerge >/dev/null; }
trap 'remove_package || true; rm -rf "$tmp"' EXIT
remove_package || true  # a left-over install from an earlier run

apt-get install -y -qq "$deb" > "$tmp/apt_install.log" || { cat "$tmp/apt_install.log"; fail "apt-get install $deb"; }
dpkg -L fleetmerge > "$tmp/files.txt"
echo "Depends: $(dpkg-query -W -f='${Depends}' fleetmerge)"
# (Outputs are read whole before matching: `cmd | grep -q` fails under pipefail when grep's early
# exit kills cmd with SIGPIPE.)
depends=$(dpkg-query -W -f='${Depends}' fleetmerge)
[[ $depends == *python3-numpy* ]] || fail "no python3-numpy in Depends"
[[ $depends == *libopencv-core* ]] || fail "no libopencv-core (dpkg-shlibdeps) in Depends"

multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || gcc -print-multiarch)
for f in /usr/bin/fleetmerge /usr/include/fleetmerge/fleetmerge.hpp /usr/include/fleetmerge/version.hpp \
         "/usr/lib/$multiarch/cmake/fleetmerge/fleetmergeConfig.cmake" \
         /usr/lib/python3/dist-packages/fleetmerge/__init__.py /usr/share/doc/fleetmerge/copyright; do
  grep -qx "$f" "$tmp/files.txt" || fail "the package has no $f"
done
grep -q "^/usr/lib/$multiarch/libfleetmerge\.so\." "$tmp/files.txt" || fail "no libfleetmerge.so.*"
# The commands beside `pair` (cli/main.cpp), loaded by the executable from here.
grep -qx "/usr/lib/$multiarch/fleetmerge/libfleetmerge_commands.so" "$tmp/files.txt" ||
  fail "no /usr/lib/$multiarch/fleetmerge/libfleetmerge_commands.so"
# The notices of the code linked statically into the binaries (cmake/FleetmergeDebianPackage.cmake).
for package in libceres-dev libopencv-core-dev liblz4-dev libzstd-dev libsqlite3-dev libbz2-dev; do
  grep -qx "/usr/share/doc/fleetmerge/third-party/$package.copyright" "$tmp/files.txt" ||
    fail "the package has no /usr/share/doc/fleetmerge/third-party/$package.copyright"
done
grep -q '^/usr/lib/python3/dist-packages/fleetmerge/_fleetmerge.*\.so$' "$tmp/files.txt" ||
  fail "no Python extension module"
[[ $(ldconfig -p) == *libfleetmerge.so.* ]] || fail "libfleetmerge not in the ldconfig cache"

# The command: on PATH, its version, and the demo end to end.
[ "$(command -v fleetmerge)" = /usr/bin/fleetmerge ] || fail "fleetmerge on PATH is $(command -v fleetmerge)"
version=$(dpkg-query -W -f='${Version}' fleetmerge)
[ "$(fleetmerge --version)" = "fleetmerge $version" ] || fail "fleetmerge --version: $(fleetmerge --version)"
[ "$(fleetmerge version)" = "fleetmerge $version" ] || fail "fleetmerge version: $(fleetmerge version)"
(cd "$tmp" && fleetmerge demo --out "$tmp/demo" > "$tmp/demo.txt") || { cat "$tmp/demo.txt"; fail "fleetmerge demo"; }
! grep -q "evaluation: FAILED" "$tmp/demo.txt" || { cat "$tmp/demo.txt"; fail "the demo's merge failed its evaluation"; }
[ -f "$tmp/demo/case/merged/report.json" ] || fail "the demo wrote no report.json"
echo "fleetmerge $version: --version, version and demo ok"

# The Python module from Debian's interpreter, no PYTHONPATH: same hypotheses as the command.
maps=()
while read -r m; do maps+=("$m"); done < <(find "$tmp/demo/case" -maxdepth 1 -name 'robot*.yaml' | sort)
[ ${#maps[@]} -ge 2 ] || fail "the demo case has ${#maps[@]} robot maps"
fleetmerge pair --json -n 3 "${maps[0]}" "${maps[1]}" > "$tmp/cli_pair.json"
(cd "$tmp" && env -u PYTHONPATH /usr/bin/python3 - "$version" "${maps[0]}" "${maps[1]}" "$tmp/cli_pair.json") <<'PY'
import json, sys
import fleetmerge
version, a, b, cli_json = sys.argv[1:]
assert fleetmerge.__file__.startswith("/usr/lib/python3/dist-packages/fleetmerge/"), fleetmerge.__file__
assert fleetmerge.__version__ == version, (fleetmerge.__version__, version)
got = [(h.x, h.y, h.yaw, h.omega) for h in fleetmerge.pair(a, b, n=3)]
cli = [(h["x"], h["y"], h["yaw"], h["omega"]) for h in json.load(open(cli_json))["hypotheses"]]
assert got == cli, (got, cli)
print(f"python: import fleetmerge {fleetmerge.__version__} from {fleetmerge.__file__}: pair == CLI")
PY

# The C++ consumer example against /usr: find_package with no CMAKE_PREFIX_PATH.
env -u CMAKE_PREFIX_PATH cmake -S "$source/examples/cpp_consumer" -B "$tmp/consumer" \
  -DCMAKE_BUILD_TYPE=Release > "$tmp/consumer_configure.log" || { cat "$tmp/consumer_configure.log"; fail "configure"; }
grep -q "fleetmerge_DIR:PATH=/usr/lib/$multiarch/cmake/fleetmerge" "$tmp/consumer/CMakeCache.txt" ||
  fail "find_package(fleetmerge) found $(grep fleetmerge_DIR "$tmp/consumer/CMakeCache.txt")"
cmake --build "$tmp/consumer" > "$tmp/consumer_build.log" || { cat "$tmp/consumer_build.log"; fail "build"; }
"$tmp/consumer/merge_fleet" version || fail "the header's version macros and the library's differ"
[ "$("$tmp/consumer/merge_fleet" version | cut -d' ' -f2)" = "$version" ] || fail "header version != $version"
read -r x y yaw omega < <("$tmp/consumer/merge_fleet" memory)
/usr/bin/python3 -c "import sys; x, y, yaw, o = map(float, sys.argv[1:]); \
assert abs(x - 1.0) < 0.05 and abs(y - 0.5) < 0.05 and abs(yaw) < 0.01 and o > 0.9, sys.argv" \
  "$x" "$y" "$yaw" "$omega" || fail "consumer's in-memory pair: $x $y $yaw $omega"
echo "examples/cpp_consumer built against /usr: version macros and in-memory pair ok"

# Removal leaves nothing: every path the package listed is gone, unless another package owns it
# (/usr, /usr/bin, ...). The import above wrote __pycache__ as root; prerm's py3clean removes it.
apt-get purge -y -qq fleetmerge > "$tmp/apt_purge.log" || { cat "$tmp/apt_purge.log"; fail "apt-get purge"; }
left=0
while read -r path; do
  [ -e "$path" ] || [ -L "$path" ] || continue
  dpkg -S "$path" >/dev/null 2>&1 && continue  # shared with other packages
  echo "left behind: $path" >&2
  left=$((left + 1))
done < "$tmp/files.txt"
[ -e /usr/lib/python3/dist-packages/fleetmerge ] && { echo "left behind: the module's folder" >&2; left=$((left + 1)); }
[ "$left" -eq 0 ] || fail "$left paths of the package left after apt-get purge"
[[ $(ldconfig -p) != *libfleetmerge* ]] || fail "libfleetmerge still in the ldconfig cache"
echo "apt-get purge: none of the $(wc -l < "$tmp/files.txt") paths the package listed is left"
echo "package_test: all checks passed"
