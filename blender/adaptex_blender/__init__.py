"""adaptex for Blender: unwrap a mesh with adaptex, and adapt a painted texture's layout to its
paint (a smaller texture that keeps the detail). docs/blender.md."""
import bpy
from bpy.props import BoolProperty, EnumProperty, IntProperty, StringProperty

from . import backend, meshdata

bl_info = {
    "name": "adaptex",
    "author": "adaptex",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D View / UV Editor > Sidebar > adaptex; UV Editor > UV menu",
    "description": "Unwrap with adaptex; adapt the UV layout to the painted texture (signal-adaptive "
                   "re-parameterization)",
    "category": "UV",
}


class AdaptexPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__
    backend: EnumProperty(
        name="Run adaptex with",
        items=[("AUTO", "Automatic", "The Python module where Blender can import it, else the CLI"),
               ("MODULE", "Python module", "The adaptex Python module only"),
               ("CLI", "Command line", "The adaptex command-line tool only")],
        default="AUTO")
    module_path: StringProperty(name="Module folder", subtype="DIR_PATH",
                                description="Folder holding the adaptex package (if Blender cannot import it)")
    cli_path: StringProperty(name="adaptex CLI", subtype="FILE_PATH",
                             description="The adaptex executable (default: $ADAPTEX_CLI, then PATH)")

    def draw(self, context):
        for p in ("backend", "module_path", "cli_path"):
            self.layout.prop(self, p)


def choose_backend(context):
    addon = context.preferences.addons.get(__package__)  # None when registered by a script, not enabled
    if addon is None:
        return backend.choose()
    prefs = addon.preferences
    return backend.choose(prefs.backend, bpy.path.abspath(prefs.module_path), bpy.path.abspath(prefs.cli_path))


def user_message(error):
    """\p error as the add-on's user should read it: the library and the CLI name their own flags in
    some messages ("rerun with --repair ..."), which mean nothing here; such a clause is replaced."""
    text = str(error)
    clauses = [c for c in text.split("; ") if "--" not in c]
    if len(clauses) < len(text.split("; ")):
        if "repair" in text:
            clauses.append("clean up the mesh first (Select > Select All by Trait > Non Manifold; "
                           "Mesh > Clean Up)")
        text = "; ".join(clauses)
    return text


def set_status(context, text):
    if getattr(context, "workspace", None) is not None:
        context.workspace.status_text_set(text)


def leave_edit_mode(obj):
    """Object mode for an object in edit mode (a new UV map is written to the mesh data)."""
    if obj.mode == "EDIT":
        bpy.ops.object.mode_set(mode="OBJECT")


def show_result(context, text, seconds=15.0):
    """\p text in the status bar for \p seconds (a report alone disappears after a moment)."""
    workspace = getattr(context, "workspace", None)
    if workspace is None or bpy.app.background:
        return
    workspace.status_text_set(text)

    def clear():
        try:
            workspace.status_text_set(None)
        except ReferenceError:  # the workspace was removed meanwhile
            pass

    bpy.app.timers.register(clear, first_interval=seconds)


class AdaptexJobOperator:
    """Runs prepare()'s work as a Job: in the background with a progress bar and Esc to cancel when
    invoked from the UI, synchronously from scripts (execute) and in background Blender."""
    _job = None
    _timer = None

    @classmethod
    def poll(cls, context):
        """Both operators work on the active mesh object."""
        return context.active_object is not None and context.active_object.type == "MESH"

    def execute(self, context):
        work = self.prepare(context)
        if work is None:
            return {"CANCELLED"}
        return self.finish(context, backend.Job(work).run())

    def invoke(self, context, event):
        if bpy.app.background:
            return self.execute(context)
        work = self.prepare(context)
        if work is None:
            return {"CANCELLED"}
        self._job = backend.Job(work)
        self._job.start()
        wm = context.window_manager
        wm.progress_begin(0, 100)
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.modal_handler_add(self)
        set_status(context, f"adaptex ({self.backend.name}): starting; Esc cancels")
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        job = self._job
        if event.type == "ESC" and event.value == "PRESS":
            job.cancel()
            return {"RUNNING_MODAL"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        context.window_manager.progress_update(int(100 * job.fraction))
        set_status(context, f"adaptex ({self.backend.name}): {job.phase} {100 * job.fraction:.0f}%"
                            f"{' - cancelling' if job.cancelled else '; Esc cancels'}")
        if not job.done:
            return {"PASS_THROUGH"}
        context.window_manager.event_timer_remove(self._timer)
        context.window_manager.progress_end()
        set_status(context, None)
        return self.finish(context, job)

    def finish(self, context, job):
        try:
            if isinstance(job.error, backend.Cancelled):
                self.report({"WARNING"}, "adaptex: cancelled; nothing was changed")
                return {"CANCELLED"}
            if job.error is not None:
                self.report({"ERROR"}, f"adaptex: {user_message(job.error)}; nothing was changed")
                return {"CANCELLED"}
            try:
                return self.apply(context, job.result)
            except (ValueError, RuntimeError) as e:
                self.report({"ERROR"}, f"adaptex: {user_message(e)}")
                return {"CANCELLED"}
        finally:
            self.cleanup()

    def cleanup(self):
        """Drops what prepare() made for the job only (called after every job, done or not)."""

    def target(self, context):
        """The active mesh object and its triangles, or None (with an error report)."""
        obj = context.active_object
        if obj is None or obj.type != "MESH":
            self.report({"ERROR"}, "adaptex: select a mesh object")
            return None
        leave_edit_mode(obj)
        self.object_name = obj.name
        self.V, self.F, self.loops = meshdata.triangles(obj.data)
        if len(self.F) == 0:
            self.report({"ERROR"}, "adaptex: the mesh has no faces")
            return None
        try:
            self.backend = choose_backend(context)
        except RuntimeError as e:
            self.report({"ERROR"}, f"adaptex: {e}")
            return None
        return obj

    def target_mesh(self):
        """The mesh again after the job (it may have been deleted or edited meanwhile)."""
        obj = bpy.data.objects.get(self.object_name)
        if obj is None or obj.type != "MESH":
            raise RuntimeError("the object was deleted while adaptex ran")
        me = obj.data
        me.calc_loop_triangles()
        if len(me.loop_triangles) != len(self.F):
            raise RuntimeError("the mesh was edited while adaptex ran; run it again")
        return me


class ADAPTEX_OT_unwrap(AdaptexJobOperator, bpy.types.Operator):
    triangulated = None  # with 'Triangulate first': the triangulated copy the job ran on (a bpy mesh)

    """Unwrap the active mesh with adaptex (cut to disks, stretch-minimizing layout, packing) into a new UV map"""
    bl_idname = "adaptex.unwrap"
    bl_label = "Unwrap with adaptex"
    bl_options = {"REGISTER", "UNDO"}

    uv_name: StringProperty(name="UV map", default="adaptex", description="Name of the new UV map")
    triangulate: BoolProperty(
        name="Triangulate first", default=False,
        description="Triangulate the mesh before unwrapping: adaptex cuts along triangle edges, and a seam "
                    "through a quad or n-gon cannot be stored in its UV map")

    def prepare(self, context):
        if self.target(context) is None:
            return None
        self.triangulated = None
        if self.triangulate:
            # A triangulated copy: the mesh itself changes only with the result (a failed or
            # cancelled job leaves it as it was).
            self.triangulated = meshdata.triangulated_copy(context.active_object.data)
            self.V, self.F = meshdata.triangles(self.triangulated)[:2]
        V, F, b = self.V, self.F, self.backend
        return lambda report: b.unwrap(V, F, report)

    def apply(self, context, result):
        me = self.target_mesh() if self.triangulated is None else self.write_triangulated()
        UV, FT = result
        per_loop, conflicts = meshdata.loop_uvs(me, self.loops, UV, FT)
        layer = meshdata.add_uv_map(me, self.uv_name, per_loop)
        me.update()
        msg = f"adaptex: new UV map '{layer.name}' ({self.backend.name})"
        if self.triangulated is not None:
            msg += "; the mesh was triangulated"
        if conflicts:
            msg += (f"; {conflicts} polygon corners lie on a seam through a polygon: run it again with "
                    "'Triangulate first' for an exact layout")
        self.report({"INFO"}, msg)
        return {"FINISHED"}

    def write_triangulated(self):
        """The object's mesh replaced by the triangulated copy (the job's triangles), after the job."""
        obj = bpy.data.objects.get(self.object_name)
        if obj is None or obj.type != "MESH":
            raise RuntimeError("the object was deleted while adaptex ran")
        me = obj.data
        if len(me.vertices) != len(self.triangulated.vertices):
            raise RuntimeError("the mesh was edited while adaptex ran; run it again")
        meshdata.replace_geometry(me, self.triangulated)
        bpy.data.meshes.remove(self.triangulated)
        self.triangulated = None
        V, F, self.loops = meshdata.triangles(me)
        if len(F) != len(self.F) or (F != self.F).any():
            raise RuntimeError("triangulating the mesh gave other triangles than the job's")
        return me

    def cleanup(self):
        if self.triangulated is not None:
            bpy.data.meshes.remove(self.triangulated)
            self.triangulated = None


def painted_image(context, obj):
    """The image being painted: the UV editor's, else the active paint slot's, else the first image
    texture node of the active material."""
    space = getattr(context, "space_data", None)
    if space is not None and space.type == "IMAGE_EDITOR" and space.image is not None:
        return space.image
    mat = obj.active_material
    if mat is None:
        return None
    if len(mat.texture_paint_images) > 0:
        return mat.texture_paint_images[min(mat.paint_active_slot, len(mat.texture_paint_images) - 1)]
    if mat.use_nodes:
        for node in mat.node_tree.nodes:
            if node.type == "TEX_IMAGE" and node.image is not None:
                return node.image
    return None


def image_nodes(obj, image):
    """The image texture nodes of \p obj's materials that show \p image."""
    out = []
    for slot in obj.material_slots:
        mat = slot.material
        if mat is not None and mat.use_nodes:
            out += [n for n in mat.node_tree.nodes if n.type == "TEX_IMAGE" and n.image == image]
    return out


def uv_source(node):
    """Where the image node \p node takes its coordinates from, following Mapping and Reroute nodes
    upstream: (socket, uv_map_node_or_None, kind) with kind "uvmap" (a UV Map node; its map, or the
    render map when empty), "render" (unlinked, or the Texture Coordinate node's UV output: the
    render-active UV map) or "other" (not a UV map). \p socket is the input the chain starts at."""
    socket = node.inputs["Vector"]
    for _ in range(32):  # a node chain, not a cycle
        if not socket.is_linked:
            return socket, None, "render"
        link = socket.links[0]
        src = link.from_node
        if src.type == "UVMAP":
            return socket, src, "uvmap"
        if src.type == "TEX_COORD":
            return socket, None, "render" if link.from_socket.name == "UV" else "other"
        if src.type in ("MAPPING", "REROUTE", "VECT_TRANSFORM") and len(src.inputs) > 0:
            socket = src.inputs[0]
            continue
        return socket, None, "other"
    return socket, None, "other"


def painted_uv_map(obj, image):
    """The UV map \p image is painted on: the one its image texture node reads (through a UV Map
    node), else the render-active UV map (what an unlinked image node uses). None when the node's
    coordinates are not a UV map."""
    me = obj.data
    render = next((layer for layer in me.uv_layers if layer.active_render), None)
    for node in image_nodes(obj, image):
        _, uvnode, kind = uv_source(node)
        if kind == "uvmap" and uvnode.uv_map:
            return me.uv_layers.get(uvnode.uv_map)
        if kind == "other":
            return None
        return render
    return render if render is not None else me.uv_layers.active


def show_image_on(obj, old_image, new_image, uv_map_name):
    """Every image node of \p obj showing \p old_image shows \p new_image through the UV map
    \p uv_map_name, clamped at the image border (no line of the opposite border along open edges)."""
    for node in image_nodes(obj, old_image):
        socket, uvnode, kind = uv_source(node)
        node.image = new_image
        node.extension = "EXTEND"
        if kind == "uvmap":
            uvnode.uv_map = uv_map_name
        else:  # unlinked or the render UV map: an explicit UV Map node, so no other texture moves
            nt = node.id_data
            uvnode = nt.nodes.new("ShaderNodeUVMap")
            uvnode.uv_map = uv_map_name
            uvnode.location = (node.location.x - 200, node.location.y - 150)
            nt.links.new(uvnode.outputs["UV"], socket)


class ADAPTEX_OT_adapt_layout(AdaptexJobOperator, bpy.types.Operator):
    """Make the painted image N times smaller on a layout adapted to its paint (texels go where the
    paint has detail): a new UV map and a new image, keeping the originals. Shows the PSNR of the
    result and of plain downsizing; the result is assigned only when it is better"""
    bl_idname = "adaptex.adapt_layout"
    bl_label = "Adapt layout to paint"
    bl_options = {"REGISTER", "UNDO"}

    image: StringProperty(name="Image", description="The painted image (default: the one being painted)")
    scale: EnumProperty(
        name="New size",
        items=[("1", "Same size", "Keep the image size"),
               ("2", "2x smaller", "Half the width and height"),
               ("4", "4x smaller", "A quarter of the width and height (4K -> 1K)"),
               ("8", "8x smaller", "An eighth of the width and height"),
               ("CUSTOM", "Custom", "The size below")],
        default="4")
    size: IntProperty(name="Size", default=1024, min=8, max=8192, description="Width = height of the new image (Custom)")
    assign: BoolProperty(name="Show the result", default=True,
                         description="When the result beats plain downsizing: put the new image in the "
                                     "material's image nodes, through the new UV map (the originals are kept)")

    def draw(self, context):
        for p in ("image", "scale", "size", "assign"):
            self.layout.prop(self, p)

    def prepare(self, context):
        obj = self.target(context)
        if obj is None:
            return None
        img = bpy.data.images.get(self.image) if self.image else painted_image(context, obj)
        if img is None or img.size[0] == 0:
            self.report({"ERROR"}, "adaptex: no painted image (paint one, or give its name)")
            return None
        if len(obj.data.uv_layers) == 0:
            self.report({"ERROR"}, "adaptex: the mesh has no UV map")
            return None
        uv_layer = painted_uv_map(obj, img)
        if uv_layer is None:
            self.report({"ERROR"}, f"adaptex: the image '{img.name}' is not mapped by a UV map of the mesh")
            return None
        self.image, self.uv_source = img.name, uv_layer.name
        texture = meshdata.image_pixels(img)
        n = self.size if self.scale == "CUSTOM" else max(8, max(img.size) // int(self.scale))
        UV, FT = meshdata.wedges(obj.data, uv_layer, self.loops)
        self.old = (UV, FT, texture)
        V, F, b = self.V, self.F, self.backend
        return lambda report: b.make_smaller(V, F, UV, FT, texture, n, report)

    def apply(self, context, result):
        me = self.target_mesh()
        UV, FT, texture = result["UV"], result["FT"], result["texture"]
        if isinstance(texture, str):  # the CLI's PNG
            texture = meshdata.read_png(bpy, texture)
        n = texture.shape[0]
        old_uv, old_ft, old_tex = self.old
        if "psnr" in result:
            psnr_adapted, psnr_plain = result["psnr"], result["psnr_plain"]
        else:
            plain = meshdata.area_resize(old_tex, n, n)
            psnr_adapted, psnr_plain = meshdata.psnr_against(
                (old_uv, old_ft, old_tex), [(UV, FT, texture), (old_uv, old_ft, plain)], self.V, self.F)
        better = psnr_adapted > psnr_plain
        per_loop, _ = meshdata.loop_uvs(me, self.loops, UV, FT)
        active_before = me.uv_layers.active.name if me.uv_layers.active is not None else None
        layer = meshdata.add_uv_map(me, self.uv_source + "_adaptex", per_loop)
        img = meshdata.new_image(bpy, f"{self.image}_adaptex_{n}", texture)
        obj = bpy.data.objects[self.object_name]
        if self.assign and better:
            show_image_on(obj, bpy.data.images[self.image], img, layer.name)
        elif active_before is not None:
            me.uv_layers.active = me.uv_layers[active_before]  # the original stays what is shown
        me.update()
        result = {"image": img.name, "uv_map": layer.name, "size": n, "psnr": psnr_adapted,
                  "psnr_plain": psnr_plain, "gain": psnr_adapted - psnr_plain, "assigned": bool(self.assign and better),
                  "uv_source": self.uv_source, "backend": self.backend.name}
        context.scene["adaptex_last"] = result
        figures = (f"PSNR {psnr_adapted:.2f} dB adapted, {psnr_plain:.2f} dB plain downsizing to {n}x{n} "
                   f"({psnr_adapted - psnr_plain:+.2f} dB)")
        if better:
            text = f"adaptex: {n}x{n} '{img.name}', UV map '{layer.name}': {figures}"
            self.report({"INFO"}, text)
        else:
            text = (f"adaptex: not better than plain downsizing: {figures}. The original image and UV map "
                    f"stay assigned; the result is kept as '{img.name}' and UV map '{layer.name}'")
            self.report({"WARNING"}, text)
        show_result(context, text)
        return {"FINISHED"}


def draw_buttons(layout, context=None):
    layout.operator(ADAPTEX_OT_unwrap.bl_idname, icon="UV")
    layout.operator(ADAPTEX_OT_adapt_layout.bl_idname, icon="TEXTURE")
    last = context.scene.get("adaptex_last") if context is not None and context.scene is not None else None
    if last is not None and "psnr_plain" in last:  # the two PSNRs of the last result
        col = layout.column(align=True)
        col.label(text=f"Last: {last['size']}x{last['size']} '{last['image']}'")
        col.label(text=f"PSNR adapted {last['psnr']:.2f} dB")
        col.label(text=f"PSNR plain downsizing {last['psnr_plain']:.2f} dB")
        if not last.get("assigned", True):
            col.label(text="Not better: the original stays assigned", icon="ERROR")


class ADAPTEX_PT_view3d(bpy.types.Panel):
    """The adaptex tab of the 3D View's sidebar, in Object and Texture Paint mode."""
    bl_label = "adaptex"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "adaptex"

    @classmethod
    def poll(cls, context):
        return context.mode in {"OBJECT", "PAINT_TEXTURE"}

    def draw(self, context):
        draw_buttons(self.layout)


class ADAPTEX_PT_uv_editor(bpy.types.Panel):
    """The adaptex tab of the UV Editor's (Image Editor's) sidebar, in every mode."""
    bl_label = "adaptex"
    bl_space_type = "IMAGE_EDITOR"
    bl_region_type = "UI"
    bl_category = "adaptex"

    def draw(self, context):
        draw_buttons(self.layout)


def uv_menu(self, context):
    self.layout.separator()
    draw_buttons(self.layout)


classes = (AdaptexPreferences, ADAPTEX_OT_unwrap, ADAPTEX_OT_adapt_layout, ADAPTEX_PT_view3d, ADAPTEX_PT_uv_editor)


def register():
    for c in classes:
        bpy.utils.register_class(c)
    bpy.types.IMAGE_MT_uvs.append(uv_menu)
    bpy.types.VIEW3D_MT_uv_map.append(uv_menu)


def unregister():
    bpy.types.VIEW3D_MT_uv_map.remove(uv_menu)
    bpy.types.IMAGE_MT_uvs.remove(uv_menu)
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
