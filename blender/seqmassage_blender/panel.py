"""The "Mesh Massage" panel in the Properties editor's Object tab (the options are per object)."""
import bpy

from . import loader, operators, properties, schema


class _Panel:
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "object"

    @classmethod
    def poll(cls, context):
        return context.object is not None and context.object.type == "MESH"


def _prop(layout, opts, name):
    if name == "mu" and hasattr(opts, "mu_auto"):
        row = layout.row(align=True)
        row.prop(opts, "mu_auto", text="μ Auto", toggle=True)
        sub = row.row(align=True)
        sub.enabled = not opts.mu_auto
        sub.prop(opts, "mu")
    elif hasattr(opts, name + "_auto"):
        row = layout.row(align=True)
        row.prop(opts, name + "_auto", toggle=True)
        sub = row.row(align=True)
        sub.enabled = not getattr(opts, name + "_auto")
        sub.prop(opts, name)
    elif hasattr(opts, name):
        layout.prop(opts, name)


class SEQMASSAGE_PT_massage(_Panel, bpy.types.Panel):
    bl_label = "Mesh Massage"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        obj = context.object
        m = properties.module(context)
        if m is None:
            box = layout.box()
            box.label(text="seqmassage module not found", icon="ERROR")
            col = box.column(align=True)
            for line in properties._wrap(loader.status(), 60):
                col.label(text=line)
            box.operator("preferences.addon_show", text="Set Its Folder",
                         icon="PREFERENCES").module = __package__
            return
        if not properties.has_schema():
            layout.label(text="Options not built yet: open the add-on's preferences", icon="INFO")
            return
        opts = obj.seqmassage
        col = layout.column()
        for name in schema.MAIN_KEYS:
            _prop(col, opts, name)
        row = col.row()
        row.enabled = opts.weights_supported
        row.prop_search(opts, "vertex_group", obj, "vertex_groups", text="Vertex Weights")
        if not opts.weights_supported:
            col.label(text="Weights need a newer module", icon="INFO")
        col.prop(opts, "keep_original")
        layout.separator()
        keys = obj.data.shape_keys
        frames = len(keys.key_blocks) - 1 if keys else 0
        col = layout.column(align=True)
        op = col.operator(operators.SEQMASSAGE_OT_massage_shape_keys.bl_idname,
                          text=f"Massage Shape Keys ({frames})", icon="SHAPEKEY_DATA")
        op.keep_original = opts.keep_original
        op.vertex_group = opts.vertex_group if opts.weights_supported else ""
        md = operators.mesh_cache_modifier(obj)
        row = col.row()
        row.enabled = md is not None
        op = row.operator(operators.SEQMASSAGE_OT_massage_mesh_cache.bl_idname,
                          text=f"Massage Mesh Cache ({md.cache_format})" if md else
                          "Massage Mesh Cache (no modifier)", icon="MOD_MESHDEFORM")
        op.vertex_group = opts.vertex_group if opts.weights_supported else ""


class SEQMASSAGE_PT_more(_Panel, bpy.types.Panel):
    bl_label = "More Options"
    bl_parent_id = "SEQMASSAGE_PT_massage"
    bl_options = {"DEFAULT_CLOSED"}

    @classmethod
    def poll(cls, context):
        return _Panel.poll(context) and properties.has_schema()

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        opts = context.object.seqmassage
        m = properties.module(context)
        for e in schema.entries(m):
            if e["kind"] is not None and e["name"] not in schema.MAIN_KEYS:
                _prop(layout, opts, e["name"])


classes = (SEQMASSAGE_PT_massage, SEQMASSAGE_PT_more)


def register():
    for c in classes:
        bpy.utils.register_class(c)


def unregister():
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
