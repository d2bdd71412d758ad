#!/usr/bin/env bash
# Generates the input of configs/pc2_example.json without outside data: the drifting tube of
# input.synthetic (its drifted frames, written by a run that processes frame 0 only), converted to
# a PC2 point cache, out/pc2_example/input/take.pc2, with frame 0 as its mesh, rest.obj.
# Usage: tools/make_pc2_example.sh [path/to/seqmassage]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seqmassage="${1:-$root/build/src/cli/seqmassage}"
work="$root/out/pc2_example/source"
input="$root/out/pc2_example/input"
mkdir -p "$work" "$input"
cat > "$work/config.json" <<'JSON'
{ "job": "sequence",
  "input": { "synthetic": { "frames": 24, "segments": 32, "rings": 48, "drift": 0.6 } },
  "output": { "dir": "." } }
JSON
"$seqmassage" --frames 0:1 "$work/config.json" >/dev/null
/usr/bin/python3 - "$work/input" "$input" <<'PY'
import pathlib, re, struct, sys
frames = sorted(pathlib.Path(sys.argv[1]).glob("*.obj"),
                key=lambda p: [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", p.name)])
def positions(path):
    return [tuple(map(float, line.split()[1:4])) for line in path.read_text().splitlines()
            if line.startswith("v ")]
points = [positions(f) for f in frames]
out = pathlib.Path(sys.argv[2])
with open(out / "take.pc2", "wb") as f:  # little-endian: magic, version, points, start, rate, samples
    f.write(b"POINTCACHE2\0" + struct.pack("<iiffi", 1, len(points[0]), 0.0, 1.0, len(points)))
    for frame in points:
        f.write(struct.pack("<%df" % (3 * len(frame)), *[x for v in frame for x in v]))
(out / "rest.obj").write_text(frames[0].read_text())
print(f"{out / 'take.pc2'}: {len(points)} frames of {len(points[0])} points; mesh {out / 'rest.obj'}")
PY
