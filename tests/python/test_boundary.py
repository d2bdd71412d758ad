"""The Python boundary never crashes the interpreter (issue 24.5): keyword values nested far
deeper than the config reader's 64 levels, arrays whose converted copy cannot be allocated (huge
broadcast views under a memory limit), empty weights and complex arrays each end in a Python
exception with the config's words."""
import os
import pathlib
import resource
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from conftest import seqmassage, tube

MODULE_DIR = pathlib.Path(seqmassage.__file__).resolve().parent


def nested_list(depth, inner=1):
    value = inner
    for _ in range(depth):
        value = [value]
    return value


def nested_dict(depth):
    value = 1
    for _ in range(depth):
        value = {"a": value}
    return value


@pytest.fixture
def mesh():
    return tube()


def test_keyword_values_nested_50000_deep_are_refused_at_64_levels(mesh):
    vertices, triangles = mesh
    deep = nested_list(50_000)
    # The keyword arguments are the first level, "iterations" the second: the 64th list is the
    # one refused, 63 indices into the value.
    with pytest.raises(seqmassage.ConfigError) as e:
        seqmassage.Massager(vertices, triangles, iterations=deep)
    assert str(e.value) == "massage.iterations" + "[0]" * 63 + ": nested deeper than 64 levels"
    with pytest.raises(seqmassage.ConfigError) as e:
        seqmassage.Massager(vertices, triangles, iterations=nested_dict(50_000))
    assert str(e.value) == "massage.iterations" + ".a" * 63 + ": nested deeper than 64 levels"
    with pytest.raises(seqmassage.ConfigError) as e:
        seqmassage.distances(vertices, triangles, vertices, triangles, spacing=deep)
    assert str(e.value) == "measures.spacing" + "[0]" * 63 + ": nested deeper than 64 levels"
    # run_job's dict is the first level, "massage" the second.
    with pytest.raises(seqmassage.ConfigError) as e:
        seqmassage.run_job({"job": "sequence", "massage": {"iterations": deep}})
    assert str(e.value) == "massage.iterations" + "[0]" * 62 + ": nested deeper than 64 levels"
    # A list that references itself is as deep as it is followed.
    loop = []
    loop.append(loop)
    with pytest.raises(seqmassage.ConfigError, match=r"nested deeper than 64 levels$"):
        seqmassage.Massager(vertices, triangles, pinned=loop)


def test_values_within_64_levels_reach_the_config_reader(mesh):
    vertices, triangles = mesh
    # 63 lists around a number: every level accepted, then the reader's own check.
    with pytest.raises(seqmassage.ConfigError) as e:
        seqmassage.Massager(vertices, triangles, iterations=nested_list(63))
    assert "nested" not in str(e.value)
    assert str(e.value) == "massage.iterations: expected an integer >= 1, got an array"


def test_empty_weights_are_refused_like_a_file_without_numbers(mesh, tmp_path):
    vertices, triangles = mesh
    message = (f"massage.vertex_weights: expected {len(vertices)} weights (one per template "
               "vertex), got 0")
    for empty in ([], (), np.array([]), np.zeros(0, dtype=np.float32)):
        with pytest.raises(seqmassage.ConfigError) as e:
            seqmassage.Massager(vertices, triangles, vertex_weights=empty)
        assert str(e.value) == message
    (tmp_path / "none.txt").write_text("\n")
    with pytest.raises(ValueError, match=r"none\.txt has 0 weights, but the template"):
        seqmassage.Massager(vertices, triangles, vertex_weights=tmp_path / "none.txt")


def test_complex_arrays_are_a_type_error(mesh):
    vertices, triangles = mesh
    complex_vertices = vertices.astype(np.complex128)  # imaginary parts 0: still refused
    with pytest.raises(TypeError, match=r"^template_vertices: complex values \(dtype complex128\)"):
        seqmassage.Massager(complex_vertices, triangles)
    with pytest.raises(TypeError, match=r"^triangles: complex values"):
        seqmassage.Massager(vertices, triangles.astype(np.complex64))
    with pytest.raises(TypeError, match=r"^massage\.vertex_weights: complex values"):
        seqmassage.Massager(vertices, triangles, vertex_weights=np.ones(len(vertices)) + 1j)
    massager = seqmassage.Massager(vertices, triangles, iterations=1)
    with pytest.raises(TypeError, match=r"^vertices: complex values"):
        massager.run(complex_vertices)
    with pytest.raises(TypeError, match=r"^reference vertices: complex values"):
        massager.run(vertices, reference=(complex_vertices, triangles))
    with pytest.raises(TypeError, match=r"^b_vertices: complex values"):
        seqmassage.distances(vertices, triangles, complex_vertices, triangles)
    with pytest.raises(TypeError, match=r"^vertices: complex values"):
        seqmassage.shear(vertices, complex_vertices, triangles)
    # Real arrays of other dtypes and nested lists are converted as before.
    assert seqmassage.Massager(vertices.astype(np.float32), triangles).num_vertices == len(vertices)
    assert seqmassage.Massager(vertices.tolist(), triangles.tolist()).num_triangles == len(triangles)
    with pytest.raises(TypeError, match=r"^template_vertices: expected an array of numbers"):
        seqmassage.Massager(None, triangles)


# Run in a child process under a limit on its address space (ulimit -v): each case must end in a
# Python exception, the process must finish and print every line.
LIMITED = textwrap.dedent("""
    import numpy as np
    import seqmassage

    T = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])

    def nested(depth):
        value = 1
        for _ in range(depth):
            value = [value]
        return value

    huge_weights = np.broadcast_to(np.float32(1), (2**28,))   # 1 GiB as float64 ... x2
    huge_rows = np.broadcast_to(np.zeros(3), (2**27, 3))       # 3 GiB as a copy
    huge_faces = np.broadcast_to(np.array([0, 1, 2], dtype=np.int16), (2**27, 3))
    cases = {
        "weights": lambda: seqmassage.Massager(T, F, vertex_weights=huge_weights),
        "weights64": lambda: seqmassage.Massager(
            T, F, vertex_weights=np.broadcast_to(np.float64(1), (2**28,))),
        "template": lambda: seqmassage.Massager(huge_rows, F),
        "triangles": lambda: seqmassage.Massager(T, huge_faces),
        "shear": lambda: seqmassage.shear(huge_rows, huge_rows, F),
        "run": lambda: seqmassage.Massager(T, F).run(huge_rows),
        "keyword_array": lambda: seqmassage.Massager(
            T, F, iterations=np.broadcast_to(np.int64(1), (2**28,))),
        "nested": lambda: seqmassage.Massager(T, F, iterations=nested(50000)),
        "nested_job": lambda: seqmassage.run_job({"massage": {"iterations": nested(50000)}}),
        "nested_distances": lambda: seqmassage.distances(T, F, T, F, spacing=nested(50000)),
    }
    for name, case in cases.items():
        try:
            case()
            print(name, "no exception", flush=True)
        except Exception as e:
            print(name, type(e).__name__, flush=True)
    print("done", flush=True)
""")

LIMIT = 1 << 30  # 1 GiB of address space: the module loads, no copy above fits


def limited():
    resource.setrlimit(resource.RLIMIT_AS, (LIMIT, LIMIT))


def test_huge_views_and_deep_values_under_a_memory_limit_raise_not_crash():
    env = dict(os.environ, PYTHONPATH=str(MODULE_DIR), OMP_NUM_THREADS="1")
    run = subprocess.run([sys.executable, "-c", LIMITED], env=env, preexec_fn=limited,
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-2000:]
    lines = dict(line.split(" ", 1) for line in run.stdout.splitlines() if " " in line)
    assert run.stdout.splitlines()[-1] == "done"
    for name in ("weights", "weights64", "template", "triangles", "shear", "run",
                 "keyword_array"):
        assert lines[name] == "MemoryError", (name, run.stdout)
    for name in ("nested", "nested_job", "nested_distances"):
        assert lines[name] == "ConfigError", (name, run.stdout)
