"""Run by tools/bench_corrective_smooth.py inside `blender -b`: Blender's Corrective Smooth on a
folder of OBJ frames, the way a user would do it instead of seqmassage. The template frame is
imported once as the rest mesh with a shape key and a Corrective Smooth modifier (rest: the
original coordinates, the modifier's defaults otherwise); every other frame is imported with
Blender's own OBJ importer, its positions copied into the shape key, and the rest object exported
with the modifier applied by Blender's own OBJ exporter. Axes are kept as they are (no Y-up
conversion), so the output frames line up with the input's.

  blender -b --factory-startup -t 1 --python bench_corrective_smooth_blender.py -- \
      FRAMES_DIR TEMPLATE.obj OUT_DIR RESULT.json

RESULT.json: frames processed, CPU and wall seconds of the per-frame loop (import, smooth,
export) and of the set-up (template import, modifier).
"""
import array
import json
import os
import sys
import time

try:  # Blender 3.4's Python add-ons still use np.bool, which NumPy 1.24 removed
    import numpy as np

    if not hasattr(np, "bool"):
        np.bool = bool
except ImportError:
    pass

import bpy

AXES = dict(forward_axis="Y", up_axis="Z")  # no axis conversion either way


def import_obj(path):
    before = set(bpy.data.objects)
    bpy.ops.wm.obj_import(filepath=path, **AXES)
    new = [o for o in bpy.data.objects if o not in before]
    if len(new) != 1:
        raise RuntimeError(f"{path}: {len(new)} objects imported, expected 1")
    return new[0]


def coordinates(obj):
    co = array.array("f", [0.0]) * (3 * len(obj.data.vertices))
    obj.data.vertices.foreach_get("co", co)
    return co


def main():
    frames_dir, template, out_dir, result = sys.argv[sys.argv.index("--") + 1:][:4]
    os.makedirs(out_dir, exist_ok=True)
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    c0, w0 = time.process_time(), time.perf_counter()
    rest = import_obj(template)
    rest.shape_key_add(name="Basis")
    key = rest.shape_key_add(name="frame")
    key.value = 1.0
    smooth = rest.modifiers.new("CorrectiveSmooth", "CORRECTIVE_SMOOTH")
    smooth.rest_source = "ORCO"
    setup_cpu, setup_wall = time.process_time() - c0, time.perf_counter() - w0

    names = sorted(f for f in os.listdir(frames_dir) if f.endswith(".obj"))
    template_name = os.path.basename(template)
    count = 0
    c0, w0 = time.process_time(), time.perf_counter()
    for name in names:
        if name == template_name:
            continue
        frame = import_obj(os.path.join(frames_dir, name))
        co = coordinates(frame)
        if len(co) != 3 * len(rest.data.vertices):
            raise RuntimeError(f"{name}: {len(co) // 3} vertices, the template has "
                               f"{len(rest.data.vertices)}")
        mesh = frame.data
        bpy.data.objects.remove(frame)
        bpy.data.meshes.remove(mesh)
        key.data.foreach_set("co", co)
        rest.data.update()
        bpy.ops.object.select_all(action="DESELECT")
        rest.select_set(True)
        bpy.context.view_layer.objects.active = rest
        bpy.ops.wm.obj_export(filepath=os.path.join(out_dir, name), export_selected_objects=True,
                              apply_modifiers=True, export_uv=False, export_normals=False,
                              export_materials=False, **AXES)
        count += 1
    cpu, wall = time.process_time() - c0, time.perf_counter() - w0
    with open(result, "w") as out:
        json.dump({"frames": count, "cpu": cpu, "wall": wall, "setup_cpu": setup_cpu,
                   "setup_wall": setup_wall}, out)


main()
