"""The add-on as a user installs it: the zip the build writes (build/blender/
seqmassage_blender.zip, the one `cmake --install` and the .deb ship) installed through Blender's
own *Install...* (bpy.ops.preferences.addon_install), enabled, its bl_info version the module's;
with no preference set it imports the module from Python's path (where `cmake --install`, the
.deb and pip put it), and massages shape keys through Massager.run_many with the bits of
Massager.run."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bpy  # noqa: E402
import numpy as np  # noqa: E402

from support import (MODULE_DIR, check, finish, key_positions, tube_frames,  # noqa: E402
                     tube_object, work_dir)

ZIP = os.environ.get("SEQMASSAGE_ADDON_ZIP", "")


def main():
    work = work_dir("installed_zip")
    check(os.path.isfile(ZIP), f"the add-on zip exists ({ZIP})")
    scripts = os.path.join(work, "scripts")
    os.makedirs(os.path.join(scripts, "addons"))
    bpy.context.preferences.filepaths.script_directory = scripts
    bpy.utils.refresh_script_paths()
    check(bpy.ops.preferences.addon_install(filepath=ZIP, target="PREFS") == {"FINISHED"},
          "the zip installs through Blender's Install...")
    import addon_utils

    def fail(error):
        raise error

    addon_utils.enable("seqmassage_blender", default_set=True, handle_error=fail)
    addon = sys.modules["seqmassage_blender"]
    check(os.path.realpath(addon.__file__).startswith(os.path.realpath(scripts)),
          f"the add-on runs from the installed copy ({os.path.dirname(addon.__file__)})")
    # The installed module's folder on Python's path, as dist-packages is; no preference set.
    sys.path.append(MODULE_DIR)
    prefs = bpy.context.preferences.addons["seqmassage_blender"].preferences
    check(prefs.module_path == "", "no module folder in the preferences")
    m = addon.properties.module()
    check(m is not None, f"the module is found with no preference set: {addon.loader.status()}")
    version = tuple(int(x) for x in m.__version__.split("."))
    check(addon.bl_info["version"] == version,
          f"bl_info version {addon.bl_info['version']} is the module's {m.__version__}")

    frames, tris = tube_frames(frames=5)
    obj = tube_object(frames, tris, "tube_installed")
    bpy.context.view_layer.objects.active = obj
    check(bpy.ops.seqmassage.massage_shape_keys() == {"FINISHED"}, "massage_shape_keys finishes")
    template = frames[0].astype(np.float64)
    massager = m.Massager(template, tris)
    for k in range(1, len(frames)):
        want = np.asarray(massager.run(frames[k].astype(np.float64)).vertices, dtype=np.float32)
        check(np.array_equal(key_positions(obj, f"frame_{k}"), want),
              f"key frame_{k}: Massager.run's positions (float32)")


finish(main)
