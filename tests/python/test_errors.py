"""Errors: the config's checks and messages for the keyword arguments, input errors, I/O errors,
and the exception classes."""
import numpy as np
import pytest

from conftest import seqmassage, tube


@pytest.fixture
def mesh():
    return tube()


def test_exception_classes():
    assert issubclass(seqmassage.ConfigError, ValueError)
    assert issubclass(seqmassage.InputError, ValueError)
    assert issubclass(seqmassage.IoError, OSError)
    assert issubclass(seqmassage.SolverError, RuntimeError)


def test_unknown_key_has_the_configs_message(mesh):
    with pytest.raises(seqmassage.ConfigError) as e:
        seqmassage.Massager(*mesh, iteratons=10)
    assert str(e.value) == 'massage.iteratons: unknown key (did you mean "iterations"?)'


@pytest.mark.parametrize("key,value,message", [
    ("iterations", 0, "massage.iterations: expected an integer >= 1, got 0"),
    ("iterations", "ten", 'massage.iterations: expected an integer >= 1, got "ten"'),
    ("mu", 1.0, 'massage.mu: expected "auto" or a number in [0, 1), got 1.0'),
    ("solver", "direkt", 'massage.solver: expected "iterative" or "direct", got "direkt" '
                         '(did you mean "direct"?)'),
    ("lawson", 1, "massage.lawson: expected true or false, got 1"),
    ("pinned", [0, -1], "massage.pinned[1]: expected an integer >= 0, got -1"),
])
def test_bad_values_have_the_configs_messages(mesh, key, value, message):
    with pytest.raises(ValueError) as e:
        seqmassage.Massager(*mesh, **{key: value})
    assert str(e.value) == message


def test_pinned_vertex_out_of_range(mesh):
    # Checked by the engine, which names the member; the module adds the config path.
    n = len(mesh[0])
    with pytest.raises(seqmassage.ConfigError) as e:
        seqmassage.Massager(*mesh, pinned=np.array([n]))
    assert type(e.value) is seqmassage.ConfigError
    assert str(e.value) == "massage.pinned: vertex %d is out of range (the mesh has %d vertices)" % (n, n)


def test_python_values_that_are_not_json(mesh):
    with pytest.raises(ValueError, match=r"massage\.iterations: expected a JSON value"):
        seqmassage.Massager(*mesh, iterations=object())
    # numpy scalars are their Python values
    assert seqmassage.Massager(*mesh, iterations=np.int64(3)).options["iterations"] == 3


@pytest.mark.parametrize("vertices,triangles,match", [
    (np.zeros((4, 2)), [[0, 1, 2]], r"template_vertices: expected an array of shape \(n, 3\), "
                                    r"got shape \(4, 2\)"),
    (np.zeros((4, 3)), [[0, 1, 2.5]], r"triangles: expected an integer array, got dtype float64"),
    (np.zeros((4, 3)), [[0, 1, -2]], r"triangles: triangle 0 has vertex index -2"),
    (np.zeros((4, 3)), [[0, 1, 7]], r"template"),
    (np.array([[0, 0, np.nan], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]], r"template"),
])
def test_bad_template(vertices, triangles, match):
    with pytest.raises(seqmassage.InputError, match=match):
        seqmassage.Massager(vertices, triangles)


def test_bad_frame(mesh):
    vertices, triangles = mesh
    massager = seqmassage.Massager(vertices, triangles)
    with pytest.raises(ValueError, match=rf"vertices: 3 rows, the template has {len(vertices)}"):
        massager.run(vertices[:3])
    with pytest.raises(ValueError, match="reference: expected None or a mesh"):
        massager.run(vertices, reference=vertices)
    bad = vertices.copy()
    bad[3, 1] = np.inf
    with pytest.raises(seqmassage.InputError):
        massager.run(bad)


def test_run_job_errors(tmp_path):
    with pytest.raises(OSError):
        seqmassage.run_job(tmp_path / "missing.json")
    with pytest.raises(ValueError, match=r'job: expected .*got "sequense" \(did you mean "sequence"\?\)'):
        seqmassage.run_job({"job": "sequense"})
    (tmp_path / "broken.json").write_text("{")
    with pytest.raises(seqmassage.ConfigError):
        seqmassage.run_job(str(tmp_path / "broken.json"))
    with pytest.raises(seqmassage.IoError):
        seqmassage.run_job({"job": "sequence", "input": {"frames": str(tmp_path / "none")},
                            "output": {"dir": str(tmp_path / "out")}})


def test_measure_key_errors(mesh):
    with pytest.raises(ValueError) as e:
        seqmassage.distances(*mesh, *mesh, spacing=0)
    assert str(e.value) == "measures.spacing: expected a number > 0, got 0"
