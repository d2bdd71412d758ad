"""The add-on's preferences (where the module is) and the per-object options group.

The options group, `Object.seqmassage`, is built from the module's massage table when the module
loads (schema.annotations), plus the settings of the operators themselves. Without the module it
holds only the latter, and the panel says why; setting the module's folder in the preferences
rebuilds it. Values are stored by name on the object, so they survive the rebuild and the file.
"""
import bpy

from . import loader, schema

_group = None  # the registered options class


def preferences(context=None):
    context = context or bpy.context
    addon = context.preferences.addons.get(__package__)
    return addon.preferences if addon else None


def module(context=None):
    """The seqmassage module, or None (loader.status() says why)."""
    prefs = preferences(context)
    return loader.load(bpy.path.abspath(prefs.module_path) if prefs and prefs.module_path else "")


def has_schema():
    return _group is not None and getattr(_group, "from_schema", False)


def _module_path_changed(self, context):
    if not has_schema() and module(context) is not None:
        register_options()


class SEQMASSAGE_AP_preferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    module_path: bpy.props.StringProperty(
        name="Module folder", subtype="DIR_PATH", update=_module_path_changed,
        description="Folder holding the seqmassage Python module (seqmassage*.so), e.g. a "
                    "checkout's build/python; not needed when the module is installed (the .deb, "
                    "cmake --install, pip) where Blender's Python finds it, on PYTHONPATH, or "
                    "copied into the add-on's folder")

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "module_path")
        m = module(context)
        col = layout.column(align=True)
        for i, line in enumerate(_wrap(loader.status(), 90)):
            col.label(text=line, icon=("CHECKMARK" if m else "ERROR") if i == 0 else "BLANK1")


def _wrap(text, width):
    lines, line = [], ""
    for word in text.split(" "):
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}" if line else word
    return lines + [line]


def _operator_settings(weights_supported):
    weights_doc = ("Vertex group whose weights (0 to 1) say how strongly each vertex is massaged "
                   "(massage.vertex_weights): 1 fully, 0 keeps the vertex as it is; vertices "
                   "not in the group keep theirs (weight 0). Empty: every vertex fully")
    if not weights_supported:
        weights_doc += (". Needs a seqmassage module with the vertex weights feature "
                        "(massage.vertex_weights); this one has not")
    return {
        "keep_original": bpy.props.BoolProperty(
            name="Keep Original",
            description="Write the corrected positions to new shape keys named <key>.massaged "
                        "instead of replacing each key's positions"),
        "vertex_group": bpy.props.StringProperty(name="Weights", description=weights_doc),
    }


def register_options():
    """(Re)builds and registers the options group from the module's table, if it loads."""
    global _group
    unregister_options()
    m = module()
    annotations = {}
    weights_supported = False
    if m is not None:
        annotations.update(schema.annotations(m))
        weights_supported = schema.accepts(m, "vertex_weights")
    annotations.update(_operator_settings(weights_supported))
    _group = type("SEQMASSAGE_PG_options", (bpy.types.PropertyGroup,),
                  {"__annotations__": annotations, "from_schema": m is not None,
                   "weights_supported": weights_supported})
    bpy.utils.register_class(_group)
    bpy.types.Object.seqmassage = bpy.props.PointerProperty(type=_group)


def unregister_options():
    global _group
    if _group is not None:
        del bpy.types.Object.seqmassage
        bpy.utils.unregister_class(_group)
        _group = None


def register():
    bpy.utils.register_class(SEQMASSAGE_AP_preferences)
    register_options()


def unregister():
    unregister_options()
    bpy.utils.unregister_class(SEQMASSAGE_AP_preferences)
