#!/usr/bin/env bash
# installed_package_test.sh BUILD_DIR SOURCE_DIR MAPS_DIR TMP_DIR LIBDIR (ctest: installed_package)
# LIBDIR: the build's CMAKE_INSTALL_LIBDIR (lib, or lib/<multiarch> for the prefix /usr).
set -euo pipefail
build=$1 source=$2 maps=$3 tmp=$4 libdir=$5
rm -rf "$tmp" && mkdir -p "$tmp"
prefix=$tmp/prefix

cmake --install "$build" --prefix "$prefix" > "$tmp/install.log"
for f in bin/fleetmerge "$libdir/fleetmerge/libfleetmerge_commands.so" \
         include/fleetmerge/fleetmerge.hpp include/fleetmerge/version.hpp \
         "$libdir/cmake/fleetmerge/fleetmergeConfig.cmake" \
         "$libdir/cmake/fleetmerge/fleetmergeConfigVersion.cmake"; do
  [ -e "$prefix/$f" ] || { echo "FAIL: the install has no $f"; exit 1; }
done
ls "$prefix/$libdir"/libfleetmerge.so* > /dev/null
# Only the public header and the version header it includes are installed.
headers=$(find "$prefix/include" -type f | wc -l)
[ "$headers" -eq 2 ] || { echo "FAIL: $headers headers installed, expected 2"; exit 1; }

# A project outside the repository, with nothing but find_package(fleetmerge).
cmake -S "$source/examples/cpp_consumer" -B "$tmp/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_BUILD_TYPE=Release > "$tmp/consumer_configure.log"
cmake --build "$tmp/consumer" > "$tmp/consumer_build.log"
consumer=$tmp/consumer/merge_fleet

# The installed command looks for its commands module relative to itself
# (cli/commands_module.hpp): with the module set aside, its error names the prefix's path (unless
# a fleetmerge installed in the configured prefix serves it, which is said).
mv "$prefix/$libdir/fleetmerge" "$prefix/$libdir/fleetmerge.aside"
if "$prefix/bin/fleetmerge" --version > "$tmp/no_module.txt" 2>&1; then
  grep -q "^fleetmerge " "$tmp/no_module.txt" && echo "note: another installed module served the prefix's command"
else
  grep -q "$prefix/bin/../$libdir/fleetmerge/libfleetmerge_commands.so" "$tmp/no_module.txt" ||
    { cat "$tmp/no_module.txt"; echo "FAIL: the missing-module error names no prefix path"; exit 1; }
fi
mv "$prefix/$libdir/fleetmerge.aside" "$prefix/$libdir/fleetmerge"

# The header's version macros, the library's Version() and the installed command agree.
"$consumer" version
read -r _ header_version _ _ library_version < <("$consumer" version)
[ "fleetmerge $header_version" = "$("$prefix/bin/fleetmerge" --version)" ] ||
  { echo "FAIL: header $header_version, command $("$prefix/bin/fleetmerge" --version)"; exit 1; }
[ "$library_version" = "$header_version" ]

# In memory: b is a's room shifted by 20 x 10 cells of 5 cm, so b's frame is at (1.0, 0.5) in a's.
read -r x y yaw omega < <("$consumer" memory)
/usr/bin/python3 - "$x" "$y" "$yaw" "$omega" <<'PY'
import sys
x, y, yaw, omega = map(float, sys.argv[1:])
assert abs(x - 1.0) < 0.05 and abs(y - 0.5) < 0.05 and abs(yaw) < 0.01 and omega > 0.9, sys.argv
PY
echo "in-memory pair: $x $y $yaw $omega"

if [ ! -f "$maps/robotis_corridor_run1.yaml" ]; then
  echo "SKIP: real maps not found in $maps (../shared/data/maps beside the repository)"
  exit 77
fi
compare_pair() {  # the consumer's Pair equals `fleetmerge pair --json` of the installed command
  local a=$maps/$1.yaml b=$maps/$2.yaml
  "$consumer" pair "$a" "$b" 6 > "$tmp/consumer_pair.txt"
  "$prefix/bin/fleetmerge" pair --json -n 6 "$a" "$b" > "$tmp/cli_pair.json"
  /usr/bin/python3 - "$tmp/consumer_pair.txt" "$tmp/cli_pair.json" <<'PY'
import json, sys
got = [tuple(map(float, line.split())) for line in open(sys.argv[1])]
cli = [(h["x"], h["y"], h["yaw"], h["omega"]) for h in json.load(open(sys.argv[2]))["hypotheses"]]
assert got == cli and len(got) == 6, (got, cli)
PY
  echo "pair $1 $2: the consumer's 6 hypotheses equal fleetmerge pair --json"
}
compare_pair robotis_corridor_run1 robotis_corridor_run2
compare_pair lab_pair_demo_1 lab_pair_demo_2
compare_pair intel_lab intel_lab_10cm_grey

# Merge from the consumer writes the usual result set; its poses are report.json's.
"$consumer" merge "$tmp/consumer_merge" "$maps/robotis_corridor_run1.yaml" \
  "$maps/robotis_corridor_run2.yaml" "$maps/robotis_corridor_run3.yaml" > "$tmp/consumer_merge.txt"
/usr/bin/python3 - "$tmp/consumer_merge.txt" "$tmp/consumer_merge/report.json" <<'PY'
import json, sys
lines = [l.split() for l in open(sys.argv[1]) if " pose " in l]
report = json.load(open(sys.argv[2]))
for words, m in zip(lines, report["maps"]):
    assert words[0] == m["name"] and int(words[2]) == m["component"]
    assert tuple(map(float, words[4:7])) == (m["pose"]["x"], m["pose"]["y"], m["pose"]["yaw"])
assert len(lines) == len(report["maps"]) == 3
PY
echo "merge: the consumer's placements equal its report.json"

# The same consumer against the build tree, not installed (-Dfleetmerge_DIR=<build>/api): the
# build's library, with the version the install has.
cmake -S "$source/examples/cpp_consumer" -B "$tmp/build_tree_consumer" \
  -Dfleetmerge_DIR="$build/api" -DCMAKE_BUILD_TYPE=Release > "$tmp/build_tree_configure.log"
cmake --build "$tmp/build_tree_consumer" > "$tmp/build_tree_build.log"
[ "$("$tmp/build_tree_consumer/merge_fleet" version)" = "$("$consumer" version)" ]
loaded=$(ldd "$tmp/build_tree_consumer/merge_fleet" | awk '/libfleetmerge\.so/ {print $3}')
[ "$loaded" -ef "$build/api/libfleetmerge.so" ] ||
  { echo "FAIL: the build-tree consumer loads '$loaded', not the build's library"; exit 1; }
[ "$("$tmp/build_tree_consumer/merge_fleet" memory)" = "$("$consumer" memory)" ]
echo "build tree: the consumer built with -Dfleetmerge_DIR=$build/api gives the install's results"

# The README's C++ example, as printed there, compiled against the install and run.
readme=$tmp/readme_example
mkdir -p "$readme"
/usr/bin/python3 - "$source/README.md" "$readme/main.cpp" <<'PY'
import sys
text = open(sys.argv[1]).read()
code = text.split("```cpp\n#include <fleetmerge/fleetmerge.hpp>", 1)[1].split("```", 1)[0]
open(sys.argv[2], "w").write("#include <fleetmerge/fleetmerge.hpp>" + code)
PY
cat > "$readme/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.16)
project(readme_example LANGUAGES CXX)
find_package(fleetmerge CONFIG REQUIRED)
add_executable(example main.cpp)
target_link_libraries(example PRIVATE fleetmerge::fleetmerge)
CMAKE
cmake -S "$readme" -B "$readme/build" -DCMAKE_PREFIX_PATH="$prefix" > "$tmp/readme_configure.log"
cmake --build "$readme/build" > "$tmp/readme_build.log"
"$readme/build/example" "$maps/robotis_corridor_run1.yaml" "$maps/robotis_corridor_run2.yaml" \
  "$maps/robotis_corridor_run3.yaml" "$tmp/readme_merge" > "$tmp/readme_example.txt"
cat "$tmp/readme_example.txt"
# The three real runs of one corridor form one component, as `fleetmerge merge` finds them.
[ "$(grep -c ': component 0 at' "$tmp/readme_example.txt")" -eq 3 ]
[ -f "$tmp/readme_merge/report.json" ] && [ -f "$tmp/readme_merge/merged_0.yaml" ]
echo "README example: compiled against the install, 3 maps in one component"

# The Python module from the install, in Debian's layout.
site=$prefix/lib/python3/dist-packages
PYTHONPATH=$site /usr/bin/python3 -c "import fleetmerge; print('import fleetmerge', fleetmerge.__version__, 'from', fleetmerge.__file__)"
PYTHONPATH=$site /usr/bin/python3 -c "import fleetmerge, sys; sys.exit(0 if fleetmerge.__file__.startswith('$site') else 1)"
PYTHONPATH=$site /usr/bin/python3 "$source/examples/python/merge_fleet.py" "$tmp/python_merge" \
  "$maps/robotis_corridor_run1.yaml" "$maps/robotis_corridor_run2.yaml" > "$tmp/python_merge.txt"
grep -q "robotis_corridor_run2: component 0" "$tmp/python_merge.txt"
cat "$tmp/python_merge.txt"
echo "installed_package: all checks passed"
