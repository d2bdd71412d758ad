"""A script typed against the seqmassage stubs (checked by mypy --strict in test_stubs.py; it is
not run): every part of the API a pipeline uses, with the types a type checker infers."""
from typing import Any

import numpy as np
import numpy.typing as npt

import seqmassage


def massage_cache(path: str, out: str) -> list[float]:
    cache: seqmassage.PointCache = seqmassage.read_point_cache(path)
    template: npt.NDArray[np.float32] = cache.frames[0]
    triangles = np.zeros((1, 3), dtype=np.int32)
    massager = seqmassage.Massager(template, triangles, iterations=20, mu="auto",
                                   weights="mean_value", vertex_weights=np.ones(len(template)))
    results: list[seqmassage.Result] = massager.run_many(cache.frames)
    seqmassage.write_point_cache(out, [r.vertices for r in results], format="mdd")
    return [float(np.mean(seqmassage.shear(template, r.vertices, triangles))) for r in results]


def progress(frame: int, status: str, figures: dict[str, Any]) -> bool:
    print(f"frame {frame}: {status} ({figures['done']}/{figures['total']})")
    return frame < 10


def run(config: str) -> bool:
    report = seqmassage.run_job(config, progress=progress)
    one = seqmassage.Massager(np.zeros((3, 3)), [[0, 1, 2]])
    result = one.run(np.zeros((3, 3)), on_iteration=lambda stats, v: None)
    failure: str | None = result.failure
    version: str = seqmassage.__version__
    return bool(report["interrupted"]) and result.ok and failure is None and version != ""
