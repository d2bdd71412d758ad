"""tools/bench_track_eval.py (the tracking benchmark's scores) on a data set built here: a flat
grid whose truth and tracked positions differ by known offsets, so every figure has a closed
form."""
import json
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "tools"))
import bench_track_eval  # noqa: E402


def grid(n=6, spacing=1.0):
    """An n x n vertex grid in the plane z = 0, two triangles per cell, counter-clockwise from +z;
    every edge has length `spacing` or `spacing` * sqrt(2)."""
    V = np.array([[i * spacing, j * spacing, 0.0] for j in range(n) for i in range(n)])
    F = []
    for j in range(n - 1):
        for i in range(n - 1):
            a, b, c, d = j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i
            F += [(a, b, c), (a, c, d)]
    return V, np.array(F)


def write_obj(path, V, F, N=None):
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in V]
    if N is not None:
        lines += [f"vn {x!r} {y!r} {z!r}" for x, y, z in N]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in F]
    path.write_text("\n".join(lines) + "\n")


def make_dataset(root, frames):
    """frames: truth positions per frame (frame 0 = the template); raw frame k = the truth's
    surface itself (another triangulation is not needed for these checks)."""
    V, F = grid()
    (root / "raw").mkdir(parents=True)
    (root / "truth").mkdir()
    write_obj(root / "template.obj", frames[0], F)
    up = np.tile([0.0, 0.0, 1.0], (len(V), 1))
    for k, T in enumerate(frames):
        write_obj(root / "raw" / f"frame_{k:04d}.obj", T, F)
        write_obj(root / "truth" / f"frame_{k:04d}.obj", T, F, up)
    (root / "meta.json").write_text(json.dumps({"source_frames": {"count": len(frames)}}))
    return V, F


def test_errors_split_into_normal_and_tangential_parts(tmp_path):
    V, F = grid()
    # Mean edge length of the grid: 5 x 6 horizontal + 6 x 5 vertical edges of length 1 and
    # 25 diagonals of length sqrt(2), so (60 + 25 sqrt 2) / 85.
    unit = (60 + 25 * np.sqrt(2)) / 85
    lifted = V + [0.0, 0.0, 2.0]
    make_dataset(tmp_path / "set", [V, lifted])
    tracked = tmp_path / "tracked"
    tracked.mkdir()
    write_obj(tracked / "frame_0000.obj", V, F)
    # Every vertex 0.3 units along x (tangential) and 0.4 along z (normal): 0.5 in all; one
    # vertex further, 3 units along y.
    P = lifted + [0.3, 0.0, 0.4]
    P[7] += [0.0, 3.0, 0.0]
    write_obj(tracked / "frame_0001.obj", P, F)

    rows, measured_unit = bench_track_eval.score(str(tmp_path / "set"), str(tracked), False)
    assert abs(measured_unit - unit) < 1e-12
    r = rows[1]
    n = len(V)
    far = np.hypot(0.5, 3.0)
    assert abs(r["motion"] - 2.0 / unit) < 1e-12
    assert abs(r["mean"] - ((n - 1) * 0.5 + far) / n / unit) < 1e-12
    assert abs(r["max"] - far / unit) < 1e-12
    assert abs(r["normal_mean"] - 0.4 / unit) < 1e-12
    assert abs(r["tangential_mean"] - ((n - 1) * 0.3 + np.hypot(0.3, 3.0)) / n / unit) < 1e-12
    assert rows[0]["mean"] == 0.0 and rows[0]["folded"] == 0
    # Vertex 7 (row 1, column 1) moved 3 units in y, past row 4: its triangles turn over.
    assert r["folded"] > 0


def test_frames_are_matched_by_name_or_order_and_missing_ones_reported(tmp_path):
    V, F = grid()
    make_dataset(tmp_path / "set", [V, V, V])
    tracked = tmp_path / "tracked"
    tracked.mkdir()
    for k, name in enumerate(["a.obj", "b.obj", "c.obj"]):
        write_obj(tracked / name, V + [0.0, 0.0, 0.1 * k], F)
    rows, unit = bench_track_eval.score(str(tmp_path / "set"), str(tracked), False)
    assert [round(r["mean"] * unit, 12) for r in rows] == [0.0, 0.1, 0.2]

    (tracked / "c.obj").unlink()
    (tracked / "a.obj").rename(tracked / "frame_0000.obj")
    rows, _ = bench_track_eval.score(str(tmp_path / "set"), str(tracked), False)
    assert [r["status"] for r in rows] == ["ok", "missing", "missing"]
    s = bench_track_eval.summary(rows)
    assert s["frames"] == 0 and s["missing"] == 2
