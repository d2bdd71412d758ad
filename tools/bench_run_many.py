#!/usr/bin/env python3
"""Times Massager.run_many(frames) against a loop of Massager.run on the Vlasic crane (frames
1..14 against frame 0, default options): wall time, the two alternated in one process, best of
--repeat passes; and checks that both give the same bits. The loop already uses every core inside
each run (oneTBB); run_many adds the frames' parallelism on top.

  PYTHONPATH=build/python /usr/bin/python3 tools/bench_run_many.py

Not a test: it asserts nothing but the equality."""
import argparse
import pathlib
import sys
import time

import numpy as np

import seqmassage

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from bench_python import read_obj  # noqa: E402


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--data", default=str(root / ".." / "shared" / "data"),
                        help="the data folder (sequences/vlasic_crane)")
    parser.add_argument("--repeat", type=int, default=3, help="passes; the fastest is reported")
    args = parser.parse_args()
    files = sorted((pathlib.Path(args.data) / "sequences" / "vlasic_crane").glob("frame_*.obj"))
    if not files:
        sys.exit(f"no crane frames under {args.data}")
    template, triangles = read_obj(files[0])
    frames = [read_obj(f)[0] for f in files[1:]]
    massager = seqmassage.Massager(template, triangles)
    best = {"loop of run": float("inf"), "run_many": float("inf")}
    for _ in range(args.repeat):
        start = time.perf_counter()
        single = [massager.run(f) for f in frames]
        best["loop of run"] = min(best["loop of run"], time.perf_counter() - start)
        start = time.perf_counter()
        batch = massager.run_many(frames)
        best["run_many"] = min(best["run_many"], time.perf_counter() - start)
        assert all(np.array_equal(a.vertices, b.vertices) for a, b in zip(single, batch))
    print(f"crane: {len(frames)} frames of {len(template)} vertices, seqmassage "
          f"{seqmassage.__version__}, best of {args.repeat}")
    for name, seconds in best.items():
        print(f"  {name:12s} {seconds:.3f} s wall ({1000 * seconds / len(frames):.0f} ms per frame)")
    print(f"  run_many / loop: {best['run_many'] / best['loop of run']:.2f}; results identical")


if __name__ == "__main__":
    main()
