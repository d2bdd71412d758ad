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


def _first(d, *names, default=None):
    for n in names:
        if n in d and d[n] is not None:
            return d[n]
    return default


def _parse_range_text(text):
    """Choices and bounds from the reference table's "allowed" text."""
    out = {}
    choices = [c for c in re.findall(r'"([^"]*)"', text) if c != "auto"]
    if choices:
        out["choices"] = choices
    if '"auto"' in text:
        out["auto"] = True
    m = re.search(r"([\[(])\s*([-+0-9.eE]+|-inf)\s*,\s*([-+0-9.eE]+|inf)\s*([\])])", text)
    if m:
        out.update(lo=float(m.group(2)), hi=float(m.group(3)), lo_open=m.group(1) == "(",
                   hi_open=m.group(4) == ")")
    m = re.search(r"(>=|>)\s*([-+0-9.eE]+)", text)
    if m:
        out.update(lo=float(m.group(2)), lo_open=m.group(1) == ">")
    return out


def _parse_range(r):
    if r is None:
        return {}
    if isinstance(r, str):
        return _parse_range_text(r)
    if isinstance(r, dict):
        out = {}
        choices = _first(r, "choices", "names", "values", "enum")
        if choices:
            out["choices"] = [c if isinstance(c, str) else c[0] for c in choices]
        for key in ("lo", "hi", "min", "max"):
            if key in r and r[key] is not None:
                out["lo" if key in ("lo", "min") else "hi"] = float(r[key])
        for key in ("lo_open", "hi_open", "auto", "auto_word"):
            if r.get(key):
                out["auto" if key == "auto_word" else key] = True
        return out
    if isinstance(r, (list, tuple)):
        if all(isinstance(c, str) for c in r):
            return {"choices": [c for c in r if c != "auto"], "auto": "auto" in r}
        if len(r) == 2:
            return {"lo": float(r[0]) if r[0] is not None else -math.inf,
                    "hi": float(r[1]) if r[1] is not None else math.inf}
    return {}


def normalize(entry):
    """One table entry as {name, kind, default, choices, lo, hi, auto, doc}; kind None: skipped."""
    if isinstance(entry, (list, tuple)):
        entry = dict(zip(("name", "type", "default", "range", "doc"), entry))
    e = dict(entry)
    name = str(_first(e, "name", "key")).split(".")[-1]
    typ = str(_first(e, "type", default="")).lower()
    default = _first(e, "default")
    if isinstance(default, dict):  # per job: the sequence job's
        default = default.get("sequence", next(iter(default.values()), None))
    info = _parse_range(_first(e, "range", "allowed", "spec"))
    for key in ("choices", "names", "values"):
        if key in e and e[key]:
            info["choices"] = [c if isinstance(c, str) else c[0] for c in e[key]]
    for key, bound in (("min", "lo"), ("max", "hi")):  # explicit bounds over the range's text
        if key in e:
            info[bound] = float(e[key]) if e[key] is not None else (
                -math.inf if bound == "lo" else math.inf)
    if e.get("auto") or default == "auto" or "auto" in typ:
        info["auto"] = True
    doc = str(_first(e, "doc", "description", "help", default=""))
    doc = re.sub(r"`([^`]*)`", r"\1", doc)  # Markdown code spans read as plain text in a tooltip
    kind = None
    if (name in OPERATOR_KEYS or "array" in typ or "list" in typ or "path" in typ
            or "none" in typ):  # lists, paths and optional values: not a Blender property
        kind = None
    elif info.get("auto") and ("number" in typ or "float" in typ or "double" in typ):
        kind = "auto_number"
    elif "bool" in typ:
        kind = "bool"
    elif "int" in typ:
        kind = "int"
    elif "number" in typ or "float" in typ or "double" in typ:
        kind = "float"
    elif info.get("choices"):
        kind = "enum"
    return {"name": name, "kind": kind, "default": default, "doc": doc,
            "choices": info.get("choices", []), "lo": info.get("lo", -math.inf),
            "hi": info.get("hi", math.inf)}


def entries(module):
    table = module.massage_keys()
    if isinstance(table, dict):
        table = [dict(v, name=k) if isinstance(v, dict) else (k, *v) for k, v in table.items()]
    return [normalize(e) for e in table]


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
