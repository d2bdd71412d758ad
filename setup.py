"""The build of `pip install .` and `pip wheel .` (pyproject.toml): CMake configures the project
in build-pip/ (beside build/, so that ccache, with its base_dir at the checkout, shares the
objects of an earlier `cmake --build build` with the same flags) and builds only the target
seqmassage_python; the module and its type stubs (seqmassage.pyi, and the stub package
seqmassage-stubs for type checkers) go into the wheel. The version is project(VERSION) of
CMakeLists.txt, the one place it is set.

Environment: SEQMASSAGE_CMAKE_ARGS, extra arguments for the configure step (split on spaces);
SEQMASSAGE_PIP_BUILD_DIR, another build folder (relative to the checkout)."""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.build_py import build_py

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text()
    match = re.search(r"project\(seqmassage VERSION ([0-9.]+)", text)
    if not match:
        raise RuntimeError("no project(seqmassage VERSION ...) in CMakeLists.txt")
    return match.group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = ROOT / os.environ.get("SEQMASSAGE_PIP_BUILD_DIR", "build-pip")
        args = [
            "-DCMAKE_BUILD_TYPE=Release",
            # As tools/test.sh builds build/, so ccache finds the same compilations.
            "-DSEQMASSAGE_UNITY_BUILD=ON",
            "-DSEQMASSAGE_PYTHON=ON",
            "-DSEQMASSAGE_BUILD_TESTS=OFF",
            "-DSEQMASSAGE_BUILD_TOOLS=OFF",
            # The interpreter pip runs (a venv's python3 is the system's, with its headers).
            f"-DPython3_EXECUTABLE={sys.executable}",
        ]
        env = dict(os.environ)
        if shutil.which("ccache"):
            args.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
            # Paths under the checkout hashed relative to it: build/ and build-pip/ then match.
            env.setdefault("CCACHE_BASEDIR", str(ROOT))
        args += os.environ.get("SEQMASSAGE_CMAKE_ARGS", "").split()
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(min(os.cpu_count() or 1, 2))
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build)] + args, check=True, env=env)
        subprocess.run(["cmake", "--build", str(build), "--target", "seqmassage_python",
                        "-j", jobs], check=True, env=env)
        built = sorted((build / "python").glob("seqmassage*.so"))
        if not built:
            raise RuntimeError(f"the build wrote no module into {build / 'python'}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)
        stubs = ROOT / "src" / "python" / "seqmassage.pyi"
        shutil.copyfile(stubs, target.parent / "seqmassage.pyi")
        (target.parent / "seqmassage-stubs").mkdir(exist_ok=True)
        shutil.copyfile(stubs, target.parent / "seqmassage-stubs" / "__init__.pyi")


class NoPythonSources(build_py):
    """The package has no Python sources of its own; only the extension's build writes files."""

    def run(self):
        pass


setup(
    version=project_version(),
    ext_modules=[Extension("seqmassage", sources=[])],
    cmdclass={"build_ext": CMakeBuild, "build_py": NoPythonSources},
    # setuptools' own scratch folders inside build-pip/, not in CMake's build/.
    options={"build": {"build_base": str(ROOT / "build-pip" / "setuptools")}},
    zip_safe=False,
)
