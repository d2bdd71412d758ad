#!/usr/bin/env python3
"""The naive tracker of the tracking benchmark, to validate it (docs/tracking-benchmark.md).

    bench_track_baseline.py DATASET OUT [--frames N] [key=value ...]

Template = the data set's template.obj (raw frame 0); frame k is the template massaged toward raw
frame k (the remesh setting: T = the template, N = raw frame k) starting from frame k-1's
result. key=value pairs are keys of the config's `massage` object (JSON values, e.g.
iterations=30 distance_term='"plane"'). Writes OUT/frame_NNNN.obj (the template's
connectivity) and prints the seconds per frame; score OUT with bench_track_eval.py.
"""
import argparse
import json
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_track_eval import frame_count, read_obj  # noqa: E402

import seqmassage  # noqa: E402


def write_obj(path, V, F):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write("".join(f"v {x:.12g} {y:.12g} {z:.12g}\n" for x, y, z in V))
        f.write("".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F))
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dataset")
    ap.add_argument("out")
    ap.add_argument("--frames", type=int, help="track only the first N frames")
    ap.add_argument("options", nargs="*", help="massage options, key=value (value in JSON)")
    a = ap.parse_args()
    options = {}
    for o in a.options:
        key, _, value = o.partition("=")
        try:
            options[key] = json.loads(value)
        except json.JSONDecodeError:
            options[key] = value
    count = frame_count(a.dataset)
    if a.frames:
        count = min(count, a.frames)
    T, F, _ = read_obj(os.path.join(a.dataset, "template.obj"))
    F = F.astype(np.int32)
    massager = seqmassage.Massager(T, F, **options)
    os.makedirs(a.out, exist_ok=True)
    write_obj(os.path.join(a.out, "frame_0000.obj"), T, F)
    prev = T
    total = 0.0
    for k in range(1, count):
        RV, RF, _ = read_obj(os.path.join(a.dataset, "raw", f"frame_{k:04d}.obj"))
        t0 = time.perf_counter()
        result = massager.run(prev, reference=(RV, RF.astype(np.int32)))
        seconds = time.perf_counter() - t0
        total += seconds
        if result.ok:
            prev = np.array(result.vertices)
        else:
            print(f"frame {k}: failed ({result.failure}); keeping frame {k - 1}'s positions")
        write_obj(os.path.join(a.out, f"frame_{k:04d}.obj"), prev, F)
        print(f"frame {k}: {seconds:.2f} s, {len(result.iterations)} iterations, "
              f"{result.folded_triangles} folded", flush=True)
    print(f"tracked {count - 1} frames, {total / max(1, count - 1):.2f} s per frame")
    return 0


if __name__ == "__main__":
    sys.exit(main())
