#!/usr/bin/env python3
"""Times Massager.run from Python on the Vlasic crane, as bench_sequence's "optimize" stage times
the same work in C++ (Reference and Massager::run per frame against frame 0, default options):
CPU time of the calling thread, summed over frames 1..14, best of --repeat passes. Run both on
one core, so that oneTBB uses the calling thread only and the CPU times compare:

  taskset -c 0 build/tools/bench_sequence --no-job --no-memory
  taskset -c 0 env PYTHONPATH=build/python /usr/bin/python3 tools/bench_python.py

Not a test: it asserts nothing. Frames are read (in Python) before the clock starts."""
import argparse
import pathlib
import time

import numpy as np

import seqmassage


def read_obj(path):
    vertices, triangles = [], []
    for line in pathlib.Path(path).read_text().splitlines():
        words = line.split()
        if words and words[0] == "v":
            vertices.append([float(w) for w in words[1:4]])
        elif words and words[0] == "f":
            triangles.append([int(w.split("/")[0]) - 1 for w in words[1:4]])
    return np.array(vertices), np.array(triangles, dtype=np.int32)


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--data", default=str(root / ".." / "shared" / "data"),
                        help="the data folder (sequences/vlasic_crane)")
    parser.add_argument("--repeat", type=int, default=3, help="passes; the fastest is reported")
    args = parser.parse_args()
    crane = pathlib.Path(args.data) / "sequences" / "vlasic_crane"
    files = sorted(crane.glob("frame_*.obj"))
    if not files:
        raise SystemExit(f"bench_python: no frames in {crane}")
    template, triangles = read_obj(files[0])
    frames = [read_obj(f)[0] for f in files[1:]]
    massager = seqmassage.Massager(template, triangles)
    best = None
    for _ in range(args.repeat):
        cpu = wall = 0.0
        iterations = 0
        engine = 0.0  # Result.seconds: the engine's own wall time of each run
        for v in frames:
            t_cpu, t_wall = time.thread_time(), time.perf_counter()
            result = massager.run(v)
            cpu += time.thread_time() - t_cpu
            wall += time.perf_counter() - t_wall
            iterations += len(result.iterations)
            engine += result.seconds
        if best is None or cpu < best[0]:
            best = (cpu, wall, engine, iterations)
    cpu, wall, engine, iterations = best
    print(f"crane, {len(frames)} frames, {massager.num_vertices} vertices: Massager.run from "
          f"Python {cpu:.3f} s CPU of the thread ({1000 * cpu / len(frames):.1f} ms/frame), "
          f"{wall:.3f} s wall (engine's own {engine:.3f} s), {iterations} iterations "
          f"(best of {args.repeat})")


if __name__ == "__main__":
    main()
