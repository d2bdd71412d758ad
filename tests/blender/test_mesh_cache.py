"""Point caches through Blender's own Mesh Cache modifier: a PC2 and an MDD written by the add-on
load back to our positions exactly as float32; seqmassage.massage_mesh_cache writes
<name>.massaged.<ext> beside the cache (the input untouched), points the modifier at it, and the
frames it plays equal the module's results on the same frames, with lower shear. A truncated cache
is refused with a message naming the file. The command line's PC2 (output.format "pc2"), its
sequence.pc2 loaded by the modifier, gives back the OBJ run's positions to float32."""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bpy  # noqa: E402
import numpy as np  # noqa: E402

from support import (check, enable_addon, evaluated_positions, finish, log,  # noqa: E402
                     read_obj_vertices, run_cli, set_module_dir, tube_frames, tube_object,
                     work_dir, write_obj)


def cache_object(addon, frames, tris, path, fmt, name):
    obj = tube_object(frames, tris, name, shape_keys=False)
    md = obj.modifiers.new("MeshCache", "MESH_CACHE")
    md.cache_format = fmt
    md.filepath = path
    return obj, md


def played(obj, count):
    return np.array([evaluated_positions(obj, k) for k in range(count)])


def round_trip(addon, m, frames, tris, work, fmt):
    path = os.path.join(work, f"tube.{fmt.lower()}")
    addon.loader.load().write_point_cache(path, frames, format=fmt.lower())
    original = open(path, "rb").read()
    obj, md = cache_object(addon, frames, tris, path, fmt, f"tube_{fmt}")
    check(np.array_equal(played(obj, len(frames)), frames),
          f"{fmt} written by the add-on: the Mesh Cache modifier plays our positions exactly")

    bpy.context.view_layer.objects.active = obj
    check(bpy.ops.seqmassage.massage_mesh_cache() == {"FINISHED"},
          f"massage_mesh_cache on the {fmt} finishes")
    out = os.path.join(work, f"tube.massaged.{fmt.lower()}")
    check(bpy.path.abspath(md.filepath) == out, f"the modifier now reads {os.path.basename(out)}")
    check(open(path, "rb").read() == original, f"the input {fmt} is unchanged")
    got = played(obj, len(frames))
    template = frames[0].astype(np.float64)
    undrifted, _ = tube_frames(drift=0.0)
    massager = m.Massager(template, tris)
    for k in range(len(frames)):
        expected = np.asarray(massager.run(frames[k].astype(np.float64)).vertices)
        check(np.array_equal(got[k], expected.astype(np.float32)),
              f"{fmt} frame {k}: the modifier plays the module's result (float32)")
        before = float(np.mean(m.shear(template, frames[k].astype(np.float64), tris)))
        after = float(np.mean(m.shear(template, got[k].astype(np.float64), tris)))
        if k:
            # The tube bends, so even its undrifted frames have shear against the straight
            # template (their floor): on frames 4 and 5 more than half the drifted frames'.
            floor = float(np.mean(m.shear(template, undrifted[k].astype(np.float64), tris)))
            log(f"{fmt} frame {k}: mean shear {before:.5f} -> {after:.5f} "
                f"(undrifted {floor:.5f})")
            check(after < before, f"{fmt} frame {k}: mean shear lower")
    return path


def truncated(addon, frames, tris, work, path):
    bad = os.path.join(work, "short.pc2")
    with open(bad, "wb") as f:
        f.write(open(path, "rb").read()[:-12])
    obj, md = cache_object(addon, frames, tris, bad, "PC2", "short")
    bpy.context.view_layer.objects.active = obj
    try:
        bpy.ops.seqmassage.massage_mesh_cache()
        raised = ""
    except RuntimeError as e:
        raised = str(e)
    check("short.pc2" in raised and "bytes" in raised,
          f"a truncated PC2 is refused, naming it: {raised.strip()}")
    check(not os.path.exists(os.path.join(work, "short.massaged.pc2")), "and nothing is written")


def cli_pc2(addon, frames, tris, work):
    """The command line's own PC2 output (output.format "pc2"), played by the modifier: the OBJ
    run's positions as float32, every frame."""
    folder = os.path.join(work, "frames")
    os.makedirs(folder)
    for k, frame in enumerate(frames):
        write_obj(os.path.join(folder, f"frame_{k}.obj"), frame, tris)
    runs = {}
    for fmt in ("obj", "pc2"):
        config = {"job": "sequence", "input": {"frames": "frames"}, "template": {"frame": 0},
                  "output": {"dir": f"out_{fmt}", "format": fmt, "timings": False}, "threads": 1}
        path = os.path.join(work, f"config_{fmt}.json")
        with open(path, "w") as f:
            json.dump(config, f)
        runs[fmt] = path
    run_cli(runs["obj"])
    run_cli(runs["pc2"])
    pc2 = os.path.join(work, "out_pc2", "sequence.pc2")
    obj, md = cache_object(addon, frames, tris, pc2, "PC2", "tube_cli")
    got = played(obj, len(frames))
    want = [read_obj_vertices(os.path.join(work, "out_obj", "frames", f"frame_{k}.obj"))
            for k in range(len(frames))]
    check(all(np.array_equal(got[k], want[k].astype(np.float32)) for k in range(len(frames))),
          "the command line's sequence.pc2 plays its OBJ run's positions to float32")


def main():
    work = work_dir("mesh_cache")
    addon = enable_addon()
    set_module_dir()
    m = addon.properties.module()
    check(m is not None, "module loaded from the preferences folder")
    frames, tris = tube_frames()
    pc2 = round_trip(addon, m, frames, tris, work, "PC2")
    round_trip(addon, m, frames, tris, work, "MDD")
    truncated(addon, frames, tris, work, pc2)
    cli_pc2(addon, frames, tris, work)


finish(main)
