#!/usr/bin/env python3
"""seqmassage against Blender's Corrective Smooth on a long capture, in one run (issue 29).

The full-rate Vlasic crane (../shared/data/sequences/vlasic_crane_full: crane.pc2 + rest.obj,
175 frames of 10,002 vertices) is written out as OBJ frames (the rest mesh's faces, each frame's
float32 positions printed as the source OBJ files print them, %g), then processed both ways:

  seqmassage  the default sequence job, template frame 0, per-triangle CSVs, `--quiet --threads N`
              for each N of --threads (default 1,2);
  Blender     Corrective Smooth headless (`blender -b -t 1`), through Blender's own OBJ import and
              export (tools/bench_corrective_smooth_blender.py), when blender is installed.

Each is timed from outside (CPU = user + system of the child, and wall), best of --repeat; the
table gives CPU and wall per optimized frame and seqmassage's CPU per frame over Blender's. Then
bench_sequence's per-stage split (one thread, CPU time) on the same OBJ frames, unless
--no-stages. Prints timings; asserts nothing.

  python3 tools/bench_corrective_smooth.py [--build build] [--data DIR] [--frames N]
      [--threads 1,2] [--repeat 1] [--seqmassage PATH ...] [--no-blender] [--no-stages] [--keep DIR]

Several --seqmassage builds are timed side by side (alternating, per repeat), for before/after.
"""
import argparse
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def write_frames(pc2, rest, out, limit):
    """OBJ frames frame_0000.obj ... of the cache's samples (at most `limit`), rest.obj's faces."""
    faces = []
    with open(rest) as f:
        for line in f:
            if line.startswith("f "):
                faces.append(line)
    faces = "".join(faces)
    with open(pc2, "rb") as f:
        magic, version, points, _start, _rate, samples = struct.unpack("<12siiffi", f.read(32))
        if magic != b"POINTCACHE2\0" or version != 1:
            raise SystemExit(f"{pc2}: not a PC2 file")
        count = min(samples, limit) if limit else samples
        os.makedirs(out, exist_ok=True)
        for k in range(count):
            xyz = struct.unpack(f"<{3 * points}f", f.read(12 * points))
            lines = ["v %g %g %g\n" % xyz[3 * i:3 * i + 3] for i in range(points)]
            with open(os.path.join(out, "frame_%04d.obj" % k), "w") as obj:
                obj.write("".join(lines))
                obj.write(faces)
    return count, points


def timed(cmd, log):
    """Runs cmd, returns (ok, cpu seconds of the child, wall seconds)."""
    t0 = time.perf_counter()
    with open(log, "w") as out:
        proc = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode == 0, usage.ru_utime + usage.ru_stime, wall


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data"))
    ap.add_argument("--frames", type=int, default=0, help="first N frames only (default all)")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--seqmassage", action="append", help="executable(s) to time (default: "
                    "BUILD/seqmassage); several are alternated")
    ap.add_argument("--no-blender", action="store_true")
    ap.add_argument("--no-stages", action="store_true")
    ap.add_argument("--keep", help="scratch folder, kept")
    a = ap.parse_args()

    source = os.path.join(a.data, "sequences", "vlasic_crane_full")
    if not os.path.exists(os.path.join(source, "crane.pc2")):
        print(f"bench_corrective_smooth: skipped, {source} not found")
        return 0
    scratch = a.keep or tempfile.mkdtemp(prefix="bench_corrective_smooth.")
    frames_dir = os.path.join(scratch, "frames")
    count, points = write_frames(os.path.join(source, "crane.pc2"), os.path.join(source, "rest.obj"),
                                 frames_dir, a.frames)
    optimized = count - 1
    print(f"crane, full rate: {count} OBJ frames of {points} vertices ({optimized} optimized, "
          f"template frame 0), scratch {scratch}")

    builds = a.seqmassage or [os.path.join(a.build, "src", "cli", "seqmassage")]
    rows = []  # (label, cpu, wall)
    best = {}
    for r in range(a.repeat):
        for b, exe in enumerate(builds):
            for threads in [int(t) for t in a.threads.split(",")]:
                out = os.path.join(scratch, f"out{b}_{threads}")
                shutil.rmtree(out, ignore_errors=True)
                config = os.path.join(scratch, f"crane{b}_{threads}.json")
                with open(config, "w") as f:
                    json.dump({"job": "sequence", "input": {"frames": frames_dir},
                               "template": {"frame": 0},
                               "output": {"dir": out, "per_triangle_csv": True}}, f)
                ok, cpu, wall = timed([exe, config, "--quiet", "--threads", str(threads)],
                                      os.path.join(scratch, "seqmassage.log"))
                key = (b, threads)
                if not ok:
                    print(f"  {exe} --threads {threads}: FAILED, see {scratch}/seqmassage.log")
                    continue
                if key not in best or cpu < best[key][0]:
                    best[key] = (cpu, wall)
    for (b, threads), (cpu, wall) in sorted(best.items()):
        label = f"seqmassage{'' if len(builds) == 1 else ' [' + str(b) + ']'}, {threads} thread(s)"
        rows.append((label, cpu, wall))

    blender = shutil.which("blender")
    reference = None
    if blender and not a.no_blender:
        script = os.path.join(ROOT, "tools", "bench_corrective_smooth_blender.py")
        for r in range(a.repeat):
            result = os.path.join(scratch, "blender.json")
            cmd = [blender, "-b", "--factory-startup", "-t", "1", "--python-exit-code", "1",
                   "--python", script, "--", frames_dir, os.path.join(frames_dir, "frame_0000.obj"),
                   os.path.join(scratch, "blender_out"), result]
            env_ok, cpu, wall = timed(cmd, os.path.join(scratch, "blender.log"))
            if not env_ok or not os.path.exists(result):
                print(f"  blender: FAILED, see {scratch}/blender.log")
                break
            inner = json.load(open(result))
            if reference is None or cpu < reference[0]:
                reference = (cpu, wall, inner)
        if reference:
            rows.append(("Blender Corrective Smooth, 1 thread", reference[0], reference[1]))
    elif not blender:
        print("  blender not installed: Corrective Smooth skipped")

    print(f"\nwhole runs, timed from outside (start-up, reading and writing included), best of "
          f"{a.repeat}; per optimized frame ({optimized}):")
    print(f"  {'':44} {'CPU s':>8} {'wall s':>8} {'CPU ms/frame':>13} {'wall ms/frame':>14}"
          f" {'CPU vs Blender':>15}")
    for label, cpu, wall in rows:
        ratio = f"{cpu / reference[0]:.2f}x" if reference else "-"
        print(f"  {label:44} {cpu:8.2f} {wall:8.2f} {1e3 * cpu / optimized:13.1f}"
              f" {1e3 * wall / optimized:14.1f} {ratio:>15}")
    if reference:
        inner = reference[2]
        print(f"  Blender inside: set-up {inner['setup_cpu']:.2f} s CPU; per frame (import, "
              f"smooth, export) {1e3 * inner['cpu'] / max(inner['frames'], 1):.1f} ms CPU, "
              f"{1e3 * inner['wall'] / max(inner['frames'], 1):.1f} ms wall")

    bench = os.path.join(a.build, "tools", "bench_sequence")
    if not a.no_stages and os.path.exists(bench):
        print("\nper-stage split (bench_sequence --stages-dir, one thread, CPU time):", flush=True)
        subprocess.run([bench, "--stages-dir", frames_dir, "--quiet-frames", "--no-job",
                        "--no-memory"], check=False)
    if not a.keep:
        shutil.rmtree(scratch, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
