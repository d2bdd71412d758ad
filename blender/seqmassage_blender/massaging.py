"""Massaging frames with the module, and measuring them: what both operators share (no bpy).

Frames run in batches through Massager.run_many, which massages a batch in parallel on the
module's threads (TBB, the GIL released) and gives each frame the bits Massager.run gives it; an
operator runs one batch per step, so that between batches Blender redraws its progress and sees
Esc. Each frame's result is independent of the others.
"""
import os

import numpy as np


class FrameResult:
    """One frame: `vertices` (n x 3 float32, as Blender stores them; the input's when the frame
    failed), `ok`, `failure`, `iterations`, and mean shear (eq. 8) against the template before
    and after."""

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


def batch_size():
    """Frames per step: one per core, so that a step keeps every core busy once."""
    return max(1, os.cpu_count() or 1)


def run_batch(module, massager, template, triangles, frames):
    """FrameResults of `frames` (n x 3 arrays), massaged in parallel by Massager.run_many."""
    inputs = [np.ascontiguousarray(f, dtype=np.float64) for f in frames]
    out = []
    for vertices, result in zip(inputs, massager.run_many(inputs)):
        ok = bool(result.ok)
        moved = np.asarray(result.vertices, dtype=np.float64) if ok else vertices
        out.append(FrameResult(moved.astype(np.float32), ok, result.failure or "",
                               list(result.iterations),
                               mean_shear(module, template, vertices, triangles),
                               mean_shear(module, template, moved, triangles)))
    return out


class Batches:
    """`frames` (a sequence of n x 3 arrays) massaged a batch at a time: step() runs the next batch
    and says whether any is left; `results` holds the FrameResults so far, in order."""

    def __init__(self, module, massager, template, triangles, frames, size=0):
        self.module, self.massager = module, massager
        self.template, self.triangles, self.frames = template, triangles, frames
        self.size = size or batch_size()
        self.results = []

    @property
    def total(self):
        return len(self.frames)

    def step(self):
        start = len(self.results)
        stop = min(start + self.size, self.total)
        self.results += run_batch(self.module, self.massager, self.template, self.triangles,
                                  [self.frames[k] for k in range(start, stop)])
        return len(self.results) < self.total


def describe(name, r):
    """One report line: `name: mean shear 0.0123 -> 0.0045 (9 iterations)`."""
    if not r.ok:
        return f"{name}: FAILED ({r.failure}), left as it was; mean shear {r.shear_before:.4g}"
    return (f"{name}: mean shear {r.shear_before:.4g} -> {r.shear_after:.4g} "
            f"({len(r.iterations)} iterations)")
