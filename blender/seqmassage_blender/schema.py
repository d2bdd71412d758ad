"""Blender properties built from the module's massage option table (seqmassage.massage_keys()).

Every key of the config's `massage` object that a Blender property can hold becomes one: a
boolean, an integer or a number with the table's range, a string with a fixed set of values an
enum, and "auto" or a number two properties (`<key>_auto` and `<key>`). Keys that hold lists or
paths (pinned vertices, a weights file) are left to the operators. Only values that differ from
the table's default are passed to the Massager, so that a run with untouched settings is the
config's default run; numbers go through float32 (what Blender stores) and back by their shortest
decimal form, so 0.7 in the panel is 0.7 in the run, as in a JSON config.
"""
import math
import re

import numpy as np

# Shown in the panel itself; the rest go to the "More options" sub-panel.
MAIN_KEYS = ("iterations", "mu", "weights", "shape_target")
# Held by the operators (a vertex group, the mesh's own boundary), not as a setting.
OPERATOR_KEYS = ("vertex_weights", "pinned")

_INT_LIMIT = 2**31 - 1


# The Blender property kind of each massage_keys() type; the other types (lists, paths,
# optional values) are not panel settings.
_KINDS = {"boolean": "bool", "integer": "int", "number": "float", "number_or_auto": "auto_number",
          "choice": "enum"}


def normalize(entry):
    """One massage_keys() entry as {name, kind, default, choices, lo, hi, doc}; kind None: not a
    panel setting. The table's data is read as it is: type, min, max, choices."""
    name = entry["name"]
    kind = None if name in OPERATOR_KEYS else _KINDS.get(entry["type"])
    lo, hi = entry["min"], entry["max"]
    doc = re.sub(r"`([^`]*)`", r"\1", entry["doc"])  # Markdown code spans read as plain text
    return {"name": name, "kind": kind, "default": entry["default"], "doc": doc,
            "choices": list(entry["choices"] or []),
            "lo": -math.inf if lo is None else float(lo),
            "hi": math.inf if hi is None else float(hi)}


def entries(module):
    return [normalize(e) for e in module.massage_keys()]


def _label(name):
    return "μ" if name == "mu" else name.replace("_", " ").capitalize()


def annotations(module):
    """The property definitions of the options group: {identifier: bpy.props...}."""
    import bpy

    props = {}
    for e in entries(module):
        kind, name, doc, d = e["kind"], e["name"], e["doc"], e["default"]
        lo, hi = e["lo"], e["hi"]
        bounds = {}
        if kind == "int":
            if math.isfinite(lo):
                bounds["min"] = int(max(lo, -_INT_LIMIT))
            if math.isfinite(hi):
                bounds["max"] = int(min(hi, _INT_LIMIT))
            props[name] = bpy.props.IntProperty(name=_label(name), description=doc,
                                                default=int(d or 0), **bounds)
        elif kind in ("float", "auto_number"):
            if math.isfinite(lo):
                bounds["min"] = lo
            if math.isfinite(hi):
                bounds["max"] = hi
            value = float(d) if isinstance(d, (int, float)) else (lo if math.isfinite(lo) else 0.0)
            small = value != 0 and abs(value) < 1e-3
            props[name] = bpy.props.FloatProperty(name=_label(name), description=doc,
                                                  default=value, precision=6 if small else 3,
                                                  **bounds)
            if kind == "auto_number":
                props[name + "_auto"] = bpy.props.BoolProperty(
                    name="Auto", description=f'"auto" for {name}: {doc}', default=d == "auto")
        elif kind == "bool":
            props[name] = bpy.props.BoolProperty(name=_label(name), description=doc,
                                                 default=bool(d))
        elif kind == "enum":
            items = [(c, c.replace("_", " ").capitalize(), doc) for c in e["choices"]]
            props[name] = bpy.props.EnumProperty(name=_label(name), description=doc, items=items,
                                                 default=d if d in e["choices"] else items[0][0])
    return props


def _same(a, b):
    if isinstance(a, float) or isinstance(b, float):
        return np.float32(a) == np.float32(b)
    return a == b


def massage_kwargs(module, group):
    """The Massager keywords of `group` (a property group built by annotations()): the keys whose
    value is not the table's default."""
    kwargs = {}
    for e in entries(module):
        kind, name, d = e["kind"], e["name"], e["default"]
        if kind is None or not hasattr(group, name):
            continue
        if kind == "auto_number":
            value = "auto" if getattr(group, name + "_auto") else float(
                repr(np.float32(getattr(group, name))))
        elif kind == "float":
            value = float(repr(np.float32(getattr(group, name))))
        else:
            value = getattr(group, name)
        if value == "auto" and d == "auto":
            continue
        if d is not None and d != "auto" and _same(value, d):
            continue
        kwargs[name] = value
    return kwargs


def accepts(module, key):
    """Whether the module's massage table has `key` (e.g. vertex_weights)."""
    return any(e["name"] == key for e in entries(module))
