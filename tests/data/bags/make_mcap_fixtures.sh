#!/usr/bin/env bash
# Rebuilds the checked-in MCAP bags mcap_sim_seed3/robot{1,2,3}: the fleet of
# `fleetmerge simulate --robots 3 --seed 3`, robot1 zstd chunks, robot2 lz4, robot3 uncompressed
# (2 messages, to stay small), and beside them in mcap_sim_seed3/maps the maps they hold (as PNG,
# small) with truth.yaml: the simulator's output differs slightly between compilers, so the test
# compares against these rather than a fresh simulation. Needs node + npm (npm ci here), the zstd
# and lz4 tools, and Debian's /usr/bin/python3.
# Usage: tests/data/bags/make_mcap_fixtures.sh build/cli/fleetmerge
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
fleetmerge="$(realpath "$1")"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"$fleetmerge" simulate "$tmp/sim" --robots 3 --seed 3 > /dev/null
cd "$here"
[ -d node_modules ] || npm ci --no-audit --no-fund
rm -rf mcap_sim_seed3
node make_mcap.mjs --map "$tmp/sim/robot1.yaml" --out mcap_sim_seed3/robot1 --compression zstd --messages 3
node make_mcap.mjs --map "$tmp/sim/robot2.yaml" --out mcap_sim_seed3/robot2 --compression lz4 --messages 3
node make_mcap.mjs --map "$tmp/sim/robot3.yaml" --out mcap_sim_seed3/robot3 --compression none --messages 2
mkdir -p mcap_sim_seed3/maps
cp "$tmp/sim/truth.yaml" mcap_sim_seed3/maps/
/usr/bin/python3 - "$tmp/sim" mcap_sim_seed3/maps <<'PY'
import os, struct, sys, zlib
src, dst = sys.argv[1:]
def png(width, height, rows):  # 8-bit greyscale PNG, the PGM's pixels unchanged
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff))
    raw = b"".join(b"\x00" + r for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
for robot in ("robot1", "robot2", "robot3"):
    data = open(os.path.join(src, robot + ".pgm"), "rb").read()
    magic, w, h, maxval, pixels = data.split(maxsplit=4)
    w, h = int(w), int(h)
    open(os.path.join(dst, robot + ".png"), "wb").write(
        png(w, h, [pixels[j * w:(j + 1) * w] for j in range(h)]))
    yaml = open(os.path.join(src, robot + ".yaml")).read().replace(robot + ".pgm", robot + ".png")
    open(os.path.join(dst, robot + ".yaml"), "w").write(yaml)
PY
ls -l mcap_sim_seed3/*
