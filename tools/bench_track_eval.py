#!/usr/bin/env python3
"""Scores tracked frames against the truth of a tracking-benchmark data set.

    bench_track_eval.py DATASET TRACKED [--csv FILE] [--frames N] [--name NAME] [--no-distances]

DATASET is a folder written by tools/gpl/bench_track_remesh (template.obj, raw/frame_NNNN.obj,
truth/frame_NNNN.obj, meta.json; docs/tracking-benchmark.md). TRACKED is a folder of OBJ frames
with the template's vertices (in its order) and triangles: frame k is TRACKED/frame_NNNN.obj
(the raw frame's name), or else the k-th .obj file in name order when TRACKED holds exactly one
per frame.

Per frame, in mean edge lengths of the template: the error of every vertex against its truth
(mean, p95, max), split into its part along the truth surface's normal and its tangential part
(mean, p95), the mean motion of the truth since the previous frame, folded triangles (normal
opposite to the same triangle's at the true positions), and, with the seqmassage module, the Metro-style distances tracked ->
raw frame and raw frame -> tracked (mean, max; seqmassage.distances). Frame 0 is the template's
own frame; the closing line averages frames 1..N-1.
"""
import argparse
import csv
import json
import math
import os
import re
import sys

import numpy as np


def read_obj(path, want_normals=False):
    """Positions (n x 3), triangles (m x 3, 0-based, polygons fanned) and `vn` rows of an OBJ."""
    v, vn, f = [], [], []
    with open(path, "r", encoding="utf-8", errors="replace") as file:
        for line in file:
            if line.startswith("v "):
                v.append(line.split()[1:4])
            elif want_normals and line.startswith("vn "):
                vn.append(line.split()[1:4])
            elif line.startswith("f "):
                idx = [int(t.split("/")[0]) for t in line.split()[1:]]
                idx = [i - 1 if i > 0 else len(v) + i for i in idx]
                for j in range(1, len(idx) - 1):
                    f.append((idx[0], idx[j], idx[j + 1]))
    V = np.asarray(v, dtype=np.float64).reshape(-1, 3)
    F = np.asarray(f, dtype=np.int64).reshape(-1, 3)
    N = np.asarray(vn, dtype=np.float64).reshape(-1, 3) if want_normals else None
    if len(F) and (F.min() < 0 or F.max() >= len(V)):
        sys.exit(f"{path}: a face index is out of range")
    if not np.isfinite(V).all():
        sys.exit(f"{path}: a vertex position is not finite")
    return V, F, N


def mean_edge_length(V, F):
    e = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    e = np.unique(e, axis=0)
    return float(np.linalg.norm(V[e[:, 0]] - V[e[:, 1]], axis=1).mean())


def face_normals(V, F):
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return n / np.where(length > 0, length, 1.0)


def tracked_files(dataset, tracked, count):
    names = [f"frame_{k:04d}.obj" for k in range(count)]
    if all(os.path.exists(os.path.join(tracked, n)) for n in names):
        return [os.path.join(tracked, n) for n in names]
    objs = sorted(n for n in os.listdir(tracked) if n.lower().endswith(".obj"))
    if len(objs) == count:
        return [os.path.join(tracked, n) for n in objs]
    # Partial output: score the frames present under the raw frames' names.
    return [os.path.join(tracked, n) if os.path.exists(os.path.join(tracked, n)) else None
            for n in names]


def frame_count(dataset):
    """Frames of the data set: meta.json's count, or (while it is being built) the frames whose
    raw and truth files are both written."""
    meta = os.path.join(dataset, "meta.json")
    if os.path.exists(meta):
        with open(meta) as f:
            return json.load(f)["source_frames"]["count"]
    k = 0
    while all(os.path.exists(os.path.join(dataset, d, f"frame_{k:04d}.obj"))
              for d in ("raw", "truth")):
        k += 1
    return k


def load_distances():
    try:
        import seqmassage  # noqa: F401
        return seqmassage.distances
    except ImportError:
        return None


def score(dataset, tracked, with_distances=True, frames=None):
    count = frame_count(dataset) if not frames else min(frames, frame_count(dataset))
    TV, TF, _ = read_obj(os.path.join(dataset, "template.obj"))
    unit = mean_edge_length(TV, TF)
    distances = load_distances() if with_distances else None
    files = tracked_files(dataset, tracked, count)
    rows, prev_truth = [], None
    for k in range(count):
        truth, _, normal = read_obj(os.path.join(dataset, "truth", f"frame_{k:04d}.obj"), True)
        motion = (np.linalg.norm(truth - prev_truth, axis=1).mean() / unit
                  if prev_truth is not None else 0.0)
        prev_truth = truth
        row = {"frame": k, "motion": motion}
        if files[k] is None:
            row["status"] = "missing"
            rows.append(row)
            continue
        P, PF, _ = read_obj(files[k])
        if P.shape != TV.shape:
            sys.exit(f"{files[k]}: {len(P)} vertices, the template has {len(TV)}")
        if PF.shape != TF.shape or not np.array_equal(PF, TF):
            print(f"warning: {files[k]}: triangles differ from the template's", file=sys.stderr)
        e = P - truth
        en = np.einsum("ij,ij->i", e, normal)
        et = np.linalg.norm(e - en[:, None] * normal, axis=1)
        err = np.linalg.norm(e, axis=1) / unit
        en = np.abs(en) / unit
        et = et / unit
        folded = int((np.einsum("ij,ij->i", face_normals(P, TF), face_normals(truth, TF)) < 0).sum())
        row.update(status="ok", mean=err.mean(), p95=np.percentile(err, 95), max=err.max(),
                   normal_mean=en.mean(), normal_p95=np.percentile(en, 95),
                   tangential_mean=et.mean(), tangential_p95=np.percentile(et, 95),
                   folded=folded)
        if distances is not None:
            RV, RF, _ = read_obj(os.path.join(dataset, "raw", f"frame_{k:04d}.obj"))
            d = distances(P, TF.astype(np.int32), RV, RF.astype(np.int32))
            row.update(to_raw_mean=d["dist_mesh_to_ref"]["mean"] / unit,
                       to_raw_max=d["dist_mesh_to_ref"]["max"] / unit,
                       from_raw_mean=d["dist_ref_to_mesh"]["mean"] / unit,
                       from_raw_max=d["dist_ref_to_mesh"]["max"] / unit)
        rows.append(row)
    return rows, unit


COLUMNS = ["frame", "motion", "mean", "p95", "max", "normal_mean", "normal_p95",
           "tangential_mean", "tangential_p95", "to_raw_mean", "to_raw_max", "from_raw_mean",
           "from_raw_max", "folded", "status"]


def fmt(value):
    if isinstance(value, float):
        return "nan" if math.isnan(value) else f"{value:.3f}"
    return str(value)


def summary(rows):
    """Mean over frames 1..N-1 of every numeric column (frames scored), the frames missing."""
    scored = [r for r in rows[1:] if r.get("status") == "ok"]
    out = {"frames": len(scored), "missing": sum(r.get("status") == "missing" for r in rows)}
    for c in COLUMNS[1:-1]:
        vals = [r[c] for r in scored if c in r]
        if vals:
            out[c] = float(np.mean(vals)) if c != "max" else float(np.max(vals))
    out["folded"] = int(sum(r.get("folded", 0) for r in scored))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dataset")
    ap.add_argument("tracked")
    ap.add_argument("--csv", help="write the per-frame table here")
    ap.add_argument("--name", help="name of the row in the closing line (default: the data set)")
    ap.add_argument("--no-distances", action="store_true",
                    help="skip tracked <-> raw distances (no seqmassage module needed)")
    ap.add_argument("--json", help="write the closing summary here")
    ap.add_argument("--frames", type=int, help="score only the first N frames")
    a = ap.parse_args()
    rows, unit = score(a.dataset, a.tracked, not a.no_distances, a.frames)
    cols = [c for c in COLUMNS if any(c in r for r in rows)]
    print(f"# {a.dataset}: errors in mean edge lengths of the template ({unit:.6g})")
    print("| " + " | ".join(cols) + " |")
    print("|" + "---|" * len(cols))
    for r in rows:
        print("| " + " | ".join(fmt(r.get(c, float("nan"))) for c in cols) + " |")
    s = summary(rows)
    name = a.name or os.path.basename(os.path.normpath(a.dataset))
    print(f"summary {name}: frames 1..{len(rows) - 1} ({s['frames']} scored, {s['missing']} "
          f"missing): mean {s.get('mean', float('nan')):.3f}, p95 {s.get('p95', float('nan')):.3f}"
          f", max {s.get('max', float('nan')):.3f}, normal {s.get('normal_mean', float('nan')):.3f}"
          f", tangential {s.get('tangential_mean', float('nan')):.3f}, to_raw "
          f"{s.get('to_raw_mean', float('nan')):.4f}, from_raw "
          f"{s.get('from_raw_mean', float('nan')):.4f}, folded {s['folded']}")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
            w.writeheader()
            for r in rows:
                w.writerow({c: r.get(c, "") for c in cols})
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"name": name, "unit": unit, **s}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
