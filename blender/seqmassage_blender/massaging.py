"""Massaging frames with the module, and measuring them: what both operators share (no bpy).

Frames run on a thread pool: the module releases the GIL while a frame runs and one Massager may
be used from several threads at once, so the frames of a shape-key set or a cache run in
parallel, as the command line's frames do. Each frame's result is independent of the others.
"""
import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np


class FrameResult:
    """One frame: `vertices` (n x 3 float64; the input's when the frame failed), `ok`,
    `failure`, `iterations`, and mean shear (eq. 8) against the template before and after."""

    def __init__(self, vertices, ok, failure, iterations, shear_before, shear_after):
        self.vertices, self.ok, self.failure = vertices, ok, failure
        self.iterations = iterations
        self.shear_before, self.shear_after = shear_before, shear_after


def mean_shear(module, template, vertices, triangles):
    values = np.asarray(module.shear(template, vertices, triangles), dtype=np.float64)
    finite = values[np.isfinite(values)]
    return float(finite.mean()) if finite.size else float("nan")


def make_massager(module, template, triangles, kwargs, weights=None):
    """A Massager for `template` (n x 3) and `triangles` (m x 3); `weights` (n,) in [0, 1] as
    massage.vertex_weights when given. ValueError (the module's message) on a bad option."""
    kwargs = dict(kwargs)
    if weights is not None:
        kwargs["vertex_weights"] = np.ascontiguousarray(weights, dtype=np.float64)
    return module.Massager(np.ascontiguousarray(template, dtype=np.float64),
                           np.ascontiguousarray(triangles, dtype=np.int32), **kwargs)


def run_frame(module, massager, template, triangles, vertices):
    vertices = np.ascontiguousarray(vertices, dtype=np.float64)
    result = massager.run(vertices)
    ok = bool(result.ok)
    out = np.asarray(result.vertices, dtype=np.float64) if ok else vertices
    return FrameResult(out, ok, getattr(result, "failure", "") or "", list(result.iterations),
                       mean_shear(module, template, vertices, triangles),
                       mean_shear(module, template, out, triangles))


def iter_frames(module, massager, template, triangles, frames, threads=0):
    """FrameResults of `frames` (a sequence of n x 3 arrays, e.g. a memory-mapped cache), in
    order, with at most 2 x threads frames in flight, so memory does not grow with the frames."""
    threads = max(1, threads or os.cpu_count() or 1)
    total = len(frames)
    with ThreadPoolExecutor(max_workers=min(threads, max(total, 1))) as pool:
        pending = []
        submitted = 0
        for k in range(total):
            while submitted < total and len(pending) < 2 * threads:
                pending.append(pool.submit(run_frame, module, massager, template, triangles,
                                           frames[submitted]))
                submitted += 1
            yield pending.pop(0).result()


def describe(name, r):
    """One report line: `name: mean shear 0.0123 -> 0.0045 (9 iterations)`."""
    if not r.ok:
        return f"{name}: FAILED ({r.failure}), left as it was; mean shear {r.shear_before:.4g}"
    return (f"{name}: mean shear {r.shear_before:.4g} -> {r.shear_after:.4g} "
            f"({len(r.iterations)} iterations)")
