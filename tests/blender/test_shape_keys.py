"""seqmassage.massage_shape_keys on a generated drifted tube: every key comes back with lower
mean shear, and with the positions the command line gives on the same frames (an OBJ folder,
template frame 0), to float32 precision. Also: the add-on says clearly when it cannot find the
module, and finds it once its preferences name the folder."""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bpy  # noqa: E402
import numpy as np  # noqa: E402

from support import (MODULE_DIR, check, enable_addon, finish, key_positions, log,  # noqa: E402
                     read_obj_vertices, run_cli, set_module_dir, tube_frames, tube_object,
                     work_dir, write_obj)


def without_module(addon, obj):
    check(addon.properties.module() is None, "no module found before its folder is set")
    try:
        bpy.ops.seqmassage.massage_shape_keys()
        raised = ""
    except RuntimeError as e:
        raised = str(e)
    check("seqmassage module was not found" in raised and "preferences" in raised,
          f"the operator says the module is missing and where to set it: {raised[:120]}...")


def cli_frames(frames, tris, work):
    folder = os.path.join(work, "frames")
    os.makedirs(folder)
    for k, frame in enumerate(frames):
        write_obj(os.path.join(folder, f"frame_{k}.obj"), frame, tris)
    config = {"job": "sequence", "input": {"frames": "frames"}, "template": {"frame": 0, "optimize": False},
              "output": {"dir": "out", "timings": False}, "threads": 1}
    path = os.path.join(work, "config.json")
    with open(path, "w") as f:
        json.dump(config, f)
    run_cli(path)
    return [read_obj_vertices(os.path.join(work, "out", "frames", f"frame_{k}.obj"))
            for k in range(len(frames))]


def main():
    work = work_dir("shape_keys")
    addon = enable_addon()
    frames, tris = tube_frames()
    obj = tube_object(frames, tris)
    without_module(addon, obj)
    set_module_dir(MODULE_DIR)
    m = addon.properties.module()
    check(m is not None and addon.properties.has_schema(),
          "module loaded from the preferences folder; options built from massage_keys()")
    opts = obj.seqmassage
    check(opts.iterations == 15 and opts.mu_auto and opts.weights == "mean_value",
          "panel options take the schema's defaults (iterations 15, mu auto, mean_value)")

    check(bpy.ops.seqmassage.massage_shape_keys(keep_original=True) == {"FINISHED"},
          "massage_shape_keys(keep_original=True) finishes")
    names = [kb.name for kb in obj.data.shape_keys.key_blocks]
    check(all(f"frame_{k}.massaged" in names for k in range(1, len(frames))),
          "keep_original writes <key>.massaged keys")
    check(all(np.array_equal(key_positions(obj, f"frame_{k}"), frames[k])
              for k in range(1, len(frames))), "keep_original leaves the keys unchanged")

    template = np.asarray(frames[0], dtype=np.float32).astype(np.float64)
    cli = cli_frames(frames, tris, work)
    check(np.array_equal(cli[0], template),
          "the command line writes template frame 0 as it read it: the basis key's values")
    worst = 0.0
    exact = 0
    for k in range(1, len(frames)):
        got = key_positions(obj, f"frame_{k}.massaged")
        before = float(np.mean(m.shear(template, frames[k].astype(np.float64), tris)))
        after = float(np.mean(m.shear(template, got.astype(np.float64), tris)))
        log(f"frame_{k}: mean shear {before:.5f} -> {after:.5f}")
        check(after < before, f"frame_{k}: mean shear lower")
        diff = np.abs(got.astype(np.float64) - cli[k]).max()
        worst = max(worst, diff)
        exact += int(np.array_equal(got, cli[k].astype(np.float32)))
    scale = float(np.abs(template).max())
    log(f"add-on vs command line: max |diff| {worst:.3g} (coordinates up to {scale:.3g}); "
        f"{exact} of {len(frames) - 1} frames equal as float32")
    check(worst <= 2 * np.finfo(np.float32).eps * scale,
          "the add-on's positions equal the command line's to float32 precision")
    # The same doubles in (the OBJ holds the keys' float32 values exactly), the same code path:
    # the keys are the command line's positions rounded to float32, bit for bit.
    check(exact == len(frames) - 1, "every key is the command line's frame as float32")

    massaged = {k: key_positions(obj, f"frame_{k}.massaged") for k in range(1, len(frames))}
    check(bpy.ops.seqmassage.massage_shape_keys() == {"FINISHED"},
          "massage_shape_keys() (replace) finishes")
    check(all(np.array_equal(key_positions(obj, f"frame_{k}"), massaged[k])
              for k in massaged), "replacing writes the same positions into the keys")
    check(all(np.array_equal(key_positions(obj, f"frame_{k}.massaged"), massaged[k])
              for k in massaged), "keys named *.massaged are results, not frames: untouched")


finish(main)
