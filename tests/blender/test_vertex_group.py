"""A vertex group as massage.vertex_weights: the panel's Vertex Weights option names a group of the
object; its weights (0 for vertices not in the group) go to the Massager. A region at weight 0
(in the group with weight 0, or not in it) keeps exactly the input positions in every key and
in a massaged point cache; the rest is massaged as the module massages it with the same weights
as an array."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bpy  # noqa: E402
import numpy as np  # noqa: E402

from support import (check, enable_addon, evaluated_positions, finish, key_positions,  # noqa: E402
                     log, set_module_dir, tube_frames, tube_object, work_dir)


def weighted_group(obj, frames):
    """Group "massage": the lower quarter of the tube at weight 0, the next rings at 0.5, the
    upper half at 1; the rings between the quarter and the half are left out of the group."""
    z = frames[0][:, 2]
    length = float(z.max())
    zero = np.flatnonzero(z < 0.25 * length)
    half = np.flatnonzero((z >= 0.25 * length) & (z < 0.35 * length))
    full = np.flatnonzero(z >= 0.5 * length)
    group = obj.vertex_groups.new(name="massage")
    group.add(zero.tolist(), 0.0, "REPLACE")
    group.add(half.tolist(), 0.5, "REPLACE")
    group.add(full.tolist(), 1.0, "REPLACE")
    weights = np.zeros(len(z))
    weights[half], weights[full] = 0.5, 1.0
    return weights


def shape_keys(addon, m, frames, tris):
    obj = tube_object(frames, tris, "tube_weighted")
    weights = weighted_group(obj, frames)
    still = weights == 0
    check(still.sum() > 0 and (~still).sum() > 0 and (weights == 0.5).sum() > 0,
          f"the group weights {int((weights == 1).sum())} vertices 1, "
          f"{int((weights == 0.5).sum())} 0.5 and leaves {int(still.sum())} at 0")
    opts = obj.seqmassage
    check(opts.weights_supported, "the panel's Vertex Weights option is enabled")
    opts.vertex_group = "massage"
    check(bpy.ops.seqmassage.massage_shape_keys() == {"FINISHED"},
          "massage_shape_keys() with the panel's vertex group finishes")
    template = frames[0].astype(np.float64)
    massager = m.Massager(template, tris, vertex_weights=weights)
    unweighted = m.Massager(template, tris)
    for k in range(1, len(frames)):
        got = key_positions(obj, f"frame_{k}")
        check(np.array_equal(got[still], frames[k][still]),
              f"frame_{k}: the {int(still.sum())} vertices at weight 0 keep the input exactly")
        moved = np.abs(got[~still] - frames[k][~still]).max()
        free = np.asarray(unweighted.run(frames[k].astype(np.float64)).vertices)
        check(np.abs(free[still] - frames[k][still]).max() > 1e-4,
              f"frame_{k}: without weights those vertices move")
        expected = np.asarray(massager.run(frames[k].astype(np.float64)).vertices)
        check(np.array_equal(got, expected.astype(np.float32)),
              f"frame_{k}: the key is the module's result with the group's weights as an array "
              f"(the others move up to {moved:.3g})")
    opts.vertex_group = ""
    return obj


def explicit_operator_setting(frames, tris):
    """The operator's own vertex_group (a script's) overrides the panel's."""
    obj = tube_object(frames, tris, "tube_script")
    weights = weighted_group(obj, frames)
    still = weights == 0
    obj.seqmassage.vertex_group = "no such group"
    check(bpy.ops.seqmassage.massage_shape_keys(keep_original=True,
                                                vertex_group="massage") == {"FINISHED"},
          "massage_shape_keys(vertex_group='massage') overrides the panel's choice")
    got = key_positions(obj, f"frame_{len(frames) - 1}.massaged")
    check(np.array_equal(got[still], frames[-1][still]), "and its weight-0 region stays")
    try:
        bpy.ops.seqmassage.massage_shape_keys()
        raised = ""
    except RuntimeError as e:
        raised = str(e)
    check("no vertex group named 'no such group'" in raised,
          f"a missing group is an error naming it: {raised.strip()}")


def mesh_cache(addon, frames, tris, work):
    path = os.path.join(work, "tube.pc2")
    addon.loader.load().write_point_cache(path, frames, format="pc2")
    obj = tube_object(frames, tris, "tube_cache", shape_keys=False)
    weights = weighted_group(obj, frames)
    still = weights == 0
    md = obj.modifiers.new("MeshCache", "MESH_CACHE")
    md.cache_format, md.filepath = "PC2", path
    bpy.context.view_layer.objects.active = obj
    obj.seqmassage.vertex_group = "massage"
    check(bpy.ops.seqmassage.massage_mesh_cache() == {"FINISHED"},
          "massage_mesh_cache() with the panel's vertex group finishes")
    for k in range(len(frames)):
        got = evaluated_positions(obj, k)
        check(np.array_equal(got[still], frames[k][still]),
              f"cache frame {k}: the weight-0 region plays the input exactly")


def main():
    work = work_dir("vertex_group")
    addon = enable_addon()
    set_module_dir()
    m = addon.properties.module()
    check(m is not None, "module loaded from the preferences folder")
    frames, tris = tube_frames()
    shape_keys(addon, m, frames, tris)
    explicit_operator_setting(frames, tris)
    mesh_cache(addon, frames, tris, work)
    log("vertex group weights: done")


finish(main)
