"""Fixtures of the Python module's tests: the module (built into build/python), the command line
next to it, and a small generated sequence run through the command line."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

seqmassage = pytest.importorskip(
    "seqmassage",
    reason="the Python module is not built (PYTHONPATH=build/python; it needs python3-dev and "
    "pybind11-dev)")

BUILD = pathlib.Path(seqmassage.__file__).resolve().parent.parent


def read_obj(path):
    """The v and f lines of an OBJ file: (n x 3 float64, m x 3 int64, 0-based)."""
    vertices, triangles = [], []
    for line in pathlib.Path(path).read_text().splitlines():
        words = line.split()
        if words and words[0] == "v":
            vertices.append([float(w) for w in words[1:4]])
        elif words and words[0] == "f":
            triangles.append([int(w.split("/")[0]) - 1 for w in words[1:4]])
    return np.array(vertices, dtype=np.float64), np.array(triangles, dtype=np.int64)


def tube(segments=12, rings=6, radius=0.5, length=2.0):
    """A closed-ring open tube along z: (vertices, triangles)."""
    vertices = [[radius * np.cos(2 * np.pi * s / segments),
                 radius * np.sin(2 * np.pi * s / segments), length * r / rings]
                for r in range(rings + 1) for s in range(segments)]
    triangles = []
    for r in range(rings):
        for s in range(segments):
            a, b = r * segments + s, r * segments + (s + 1) % segments
            c, d = a + segments, b + segments
            triangles += [[a, b, d], [a, d, c]]
    return np.array(vertices, dtype=np.float64), np.array(triangles, dtype=np.int64)


SEQUENCE_CONFIG = {
    "job": "sequence",
    "input": {"synthetic": {"frames": 4, "segments": 16, "rings": 12, "drift": 0.6}},
    "massage": {"iterations": 6},
    "output": {"timings": False},
    "threads": 2,
}


@pytest.fixture(scope="session")
def cli_sequence(tmp_path_factory):
    """A generated drifted tube run through the command line: (output folder, report)."""
    # SEQMASSAGE_CLI: another command line (the module installed elsewhere, e.g. by pip).
    cli = pathlib.Path(os.environ.get("SEQMASSAGE_CLI", BUILD / "src" / "cli" / "seqmassage"))
    if not cli.exists():
        pytest.skip(f"the command line is not built ({cli})")
    folder = tmp_path_factory.mktemp("cli")
    config = dict(SEQUENCE_CONFIG, output=dict(SEQUENCE_CONFIG["output"], dir="out"))
    (folder / "job.json").write_text(json.dumps(config))
    subprocess.run([str(cli), "-q", "job.json"], cwd=folder, check=True)
    out = folder / "out"
    return out, json.loads((out / "report.json").read_text())
