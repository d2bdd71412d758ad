"""The type stubs (src/python/seqmassage.pyi): current with the module's options tables (the file
tools/make_stubs.py writes), covering every public name, and a typed script checked against
them with mypy (Debian's mypy, when installed)."""
import ast
import importlib.util
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

from conftest import seqmassage

ROOT = pathlib.Path(__file__).resolve().parents[2]
STUBS = ROOT / "src" / "python" / "seqmassage.pyi"


def make_stubs():
    spec = importlib.util.spec_from_file_location("make_stubs", ROOT / "tools" / "make_stubs.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.stubs()


def test_stubs_are_current():
    assert STUBS.read_text() == make_stubs(), (
        "src/python/seqmassage.pyi is stale: PYTHONPATH=build/python python3 tools/make_stubs.py")


def test_stubs_cover_every_public_name_and_massage_key():
    tree = ast.parse(STUBS.read_text())
    stubbed = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    stubbed |= {t.id for n in tree.body if isinstance(n, ast.Assign) for t in n.targets}
    stubbed |= {n.target.id for n in tree.body if isinstance(n, ast.AnnAssign)}
    public = {name for name in dir(seqmassage) if not name.startswith("_")} | {"__version__"}
    assert public - stubbed == set(), "names of the module missing from the stubs"
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    for name, node in classes.items():
        if issubclass(getattr(seqmassage, name), BaseException):
            continue  # the exceptions add nothing to their bases
        members = {m.name for m in node.body if isinstance(m, ast.FunctionDef)}
        actual = {m for m in dir(getattr(seqmassage, name)) if not m.startswith("_")}
        assert actual - members == set(), f"members of {name} missing from the stubs"
    init = next(m for m in classes["Massager"].body
                if isinstance(m, ast.FunctionDef) and m.name == "__init__")
    keywords = [a.arg for a in init.args.kwonlyargs]
    assert keywords == [k["name"] for k in seqmassage.massage_keys()]


def test_every_name_has_a_docstring():
    for name in dir(seqmassage):
        if name.startswith("_"):
            continue
        value = getattr(seqmassage, name)
        if callable(value):
            assert (value.__doc__ or "").strip(), f"{name} has no docstring"
    for cls in (seqmassage.Massager, seqmassage.Result, seqmassage.PointCache):
        for member, value in vars(cls).items():
            if not member.startswith("_"):
                assert (value.__doc__ or "").strip(), f"{cls.__name__}.{member} has no docstring"


@pytest.mark.skipif(shutil.which("mypy") is None, reason="mypy is not installed (python3 -m "
                    "pip is not used: bash tools/setup.sh installs Debian's mypy)")
def test_a_typed_script_passes_mypy_and_a_wrong_one_fails(tmp_path):
    # The stubs as a type checker finds them beside an installed module (MYPYPATH: a folder
    # holding seqmassage.pyi, the installed module's or the source's).
    stub_dir = pathlib.Path(os.environ.get("SEQMASSAGE_STUB_DIR", STUBS.parent))
    env = dict(os.environ, MYPYPATH=str(stub_dir))
    example = ROOT / "tests" / "python" / "typed_example.py"
    args = ["mypy", "--strict", "--no-incremental", "--cache-dir", str(tmp_path / "cache"),
            "--python-executable", "/usr/bin/python3"]
    ok = subprocess.run(args + [str(example)], env=env, capture_output=True, text=True)
    assert ok.returncode == 0, ok.stdout + ok.stderr
    wrong = tmp_path / "wrong.py"
    wrong.write_text("import numpy as np\nimport seqmassage\n"
                     "v = np.zeros((3, 3))\n"
                     "seqmassage.Massager(v, [[0, 1, 2]], iterations='many')\n"
                     "seqmassage.Massager(v, [[0, 1, 2]], no_such_key=1)\n")
    bad = subprocess.run(args + [str(wrong)], env=env, capture_output=True, text=True)
    assert bad.returncode != 0
    assert "iterations" in bad.stdout and "no_such_key" in bad.stdout, bad.stdout
