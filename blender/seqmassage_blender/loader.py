"""Finding and importing the seqmassage Python module.

Looked for, in order: a `seqmassage*.so` copied into this package's folder, the folder set in the
add-on's preferences (e.g. a checkout's `build/python`), then a plain `import seqmassage`: the
installed module (the .deb's /usr/lib/python3/dist-packages, `cmake --install`'s or pip's) or one
on PYTHONPATH, with no preference set. An extension module cannot be unloaded, so once one is imported it
stays for the Blender session; `status()` says which one and from where.
"""
import glob
import importlib.machinery
import importlib.util
import os
import sys

PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))

_module = None
_error = "not looked for yet"


def _import_file(path):
    loader = importlib.machinery.ExtensionFileLoader("seqmassage", path)
    spec = importlib.util.spec_from_file_location("seqmassage", path, loader=loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    sys.modules["seqmassage"] = module
    return module


def _candidates(folder):
    suffixes = importlib.machinery.EXTENSION_SUFFIXES
    found = []
    for suffix in suffixes:
        found += sorted(glob.glob(os.path.join(glob.escape(folder), "seqmassage*" + suffix)))
    return found


def load(preferences_path=""):
    """The module, or None; `status()` then says where it looked and why it failed."""
    global _module, _error
    if _module is not None:
        return _module
    if "seqmassage" in sys.modules:
        _module = sys.modules["seqmassage"]
        return _module
    tried = []
    folders = [("the add-on folder", PACKAGE_DIR)]
    if preferences_path:
        folders.append(("the preferences folder", os.path.abspath(preferences_path)))
    for label, folder in folders:
        files = _candidates(folder)
        if not files:
            tried.append(f"no seqmassage*.so in {label} ({folder})")
            continue
        try:
            _module = _import_file(files[0])
            return _module
        except ImportError as e:
            tried.append(f"{files[0]}: {e}")
    try:
        import seqmassage  # on PYTHONPATH or installed

        _module = seqmassage
        return _module
    except ImportError as e:
        tried.append(f"import seqmassage: {e}")
    _error = ("the seqmassage module was not found: " + "; ".join(tried) +
              ". Install it (the seqmassage .deb, cmake --install, or pip install), or build it "
              "(cmake, build/python) and set its folder in the add-on's preferences")
    return None


def status():
    """One line: where the module was loaded from, or why it was not."""
    if _module is not None:
        return "seqmassage module: " + getattr(_module, "__file__", "built in")
    return _error
