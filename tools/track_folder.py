#!/usr/bin/env python3
"""Track a template through a folder of OBJ frames of any connectivity with seqmassage.Tracker:
writes OUT/<frame name>.obj (the template's OBJ with the tracked positions on its `v` lines, so
texture coordinates, groups and materials are kept) and OUT/summary.csv (per-frame fit figures
in template edge lengths, status, timings); OUT/registered/ holds the registration-only
positions (before the Mesh Massage refinement), for comparing the stages. Frame 0 of the folder order is tracked from the
template as placed.

    PYTHONPATH=build/python python3 tools/track_folder.py TEMPLATE.obj FRAMES_DIR OUT_DIR \
        [--option key=value ...] [--massage key=value ...]
"""
import argparse
import json
import pathlib
import sys
import time

import numpy as np

import seqmassage


def read_obj(path):
    """v and f lines of an OBJ file: (n x 3 float64, m x 3 int64); polygons are fanned."""
    vertices, triangles = [], []
    for line in pathlib.Path(path).read_text().splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == "v":
            vertices.append([float(w) for w in words[1:4]])
        elif words[0] == "f":
            ids = [int(w.split("/")[0]) for w in words[1:]]
            ids = [i - 1 if i > 0 else len(vertices) + i for i in ids]
            triangles += [[ids[0], ids[k], ids[k + 1]] for k in range(1, len(ids) - 1)]
    return np.array(vertices, dtype=np.float64), np.array(triangles, dtype=np.int64)


def write_like(template_lines, positions, path):
    """The template's OBJ text with its v lines replaced by `positions`, written atomically."""
    out, k = [], 0
    for line in template_lines:
        if line.split()[:1] == ["v"]:
            x, y, z = positions[k]
            out.append("v %.9g %.9g %.9g" % (x, y, z))
            k += 1
        else:
            out.append(line)
    tmp = path.with_suffix(".obj.tmp")
    tmp.write_text("\n".join(out) + "\n")
    tmp.replace(path)


def value(text):
    try:
        return json.loads(text)
    except json.JSONDecodeError:
        return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("template")
    parser.add_argument("frames")
    parser.add_argument("out")
    parser.add_argument("--option", action="append", default=[], help="track key=value")
    parser.add_argument("--massage", action="append", default=[], help="massage key=value")
    args = parser.parse_args()
    options = {k: value(v) for k, v in (o.split("=", 1) for o in args.option)}
    if args.massage:
        options["massage"] = {k: value(v) for k, v in (o.split("=", 1) for o in args.massage)}
    template_lines = pathlib.Path(args.template).read_text().splitlines()
    V, F = read_obj(args.template)
    tracker = seqmassage.Tracker(V, F, **options)
    files = sorted(p for p in pathlib.Path(args.frames).iterdir() if p.suffix.lower() == ".obj")
    out = pathlib.Path(args.out)
    (out / "registered").mkdir(parents=True, exist_ok=True)
    rows = ["frame,file,status,recovery,to_raw_mean,to_raw_p99,from_raw_mean,from_raw_p99,"
            "folded,shear_mean,registration_to_raw_mean,registration_from_raw_mean,"
            "iterations,seconds_register,seconds_refine"]
    for index, path in enumerate(files):
        t0 = time.time()
        (r,) = tracker.track([read_obj(path)])
        write_like(template_lines, r["vertices"], out / path.name)
        write_like(template_lines, r["registered"], out / "registered" / path.name)
        f, g = r["fit"], r["registration_fit"]
        rows.append(",".join(str(x) for x in [
            index, path.name, r["status"], r["recovery"], f["to_raw_mean"], f["to_raw_p99"],
            f["from_raw_mean"], f["from_raw_p99"], f["folded"], f["shear_mean"],
            g["to_raw_mean"], g["from_raw_mean"], r["iterations"], r["seconds_register"],
            r["seconds_refine"]]))
        print("%s %s to_raw %.4f from_raw %.4f p99 %.3f folded %d (%.1f s)" % (
            path.name, r["status"], f["to_raw_mean"], f["from_raw_mean"], f["from_raw_p99"],
            f["folded"], time.time() - t0), file=sys.stderr)
    (out / "summary.csv").write_text("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
