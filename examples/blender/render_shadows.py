# Shadow visibility from Blender (Cycles or EEVEE) for `shadow-oracle compare --image`.
#
#   blender -b --factory-startup -P examples/blender/render_shadows.py -- VIEW.json --out DIR
#       --engine cycles|eevee [--samples N] [--eevee-soft-shadows on|off]
#       [--eevee-cube-size 512|1024|2048|4096] [--eevee-cascade-size 512|...] [--eevee-cascades N]
#       [--threads 2]
#
# Reads the view.json that `shadow-oracle view SCENE --out V` writes (view_format 1,
# docs/external.md), builds the scene in Blender and, for each light alone, renders a white Lambert
# scene twice: once as is and once with shadows off (Cycles: every object's visible_shadow = False;
# EEVEE: the light's use_shadow = False). V = shadowed / unshadowed where unshadowed > 1e-6 times
# the image's largest unshadowed value, clamped to [0, 1]; elsewhere (background, facing away from
# the light, outside a spot's cone, behind a one-sided light) V = 0, the oracle's convention.
# Writes DIR/shadows.exr (one FLOAT channel NAME.V per light, row 0 at the top) and
# DIR/shadows.exr.json (renderer, frame_ms, shadow_ms, params). Exit status 2 with one line on
# bad input, 1 on a render failure, 3 where Blender's glTF importer cannot run (no numpy).
import json
import math
import os
import struct
import sys
import tempfile
import time
from array import array

import bpy
from mathutils import Matrix, Vector


def die(msg, code=2):
    sys.stderr.write("render_shadows.py: error: %s\n" % msg)
    sys.stderr.flush()
    os._exit(code)  # sys.exit inside Blender's -P prints a traceback and may still return 0


# ---------------------------------------------------------------- arguments
def parse_args(argv):
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    opts = {"view": None, "out": None, "engine": None, "samples": None, "soft": "on",
            "cube": "512", "cascade": "1024", "cascades": 4, "threads": 2}
    flags = {"--out": "out", "--engine": "engine", "--samples": "samples",
             "--eevee-soft-shadows": "soft", "--eevee-cube-size": "cube",
             "--eevee-cascade-size": "cascade", "--eevee-cascades": "cascades",
             "--threads": "threads"}
    i = 0
    while i < len(args):
        a = args[i]
        if a in flags:
            if i + 1 >= len(args):
                die("%s needs a value" % a)
            opts[flags[a]] = args[i + 1]
            i += 2
        elif a.startswith("--"):
            die("unknown option %s" % a)
        elif opts["view"] is None:
            opts["view"] = a
            i += 1
        else:
            die("more than one VIEW.json given (%s)" % a)
    if opts["view"] is None or opts["out"] is None or opts["engine"] is None:
        die("usage: blender -b --factory-startup -P render_shadows.py -- VIEW.json --out DIR "
            "--engine cycles|eevee [--samples N] [--eevee-soft-shadows on|off] "
            "[--eevee-cube-size N] [--eevee-cascade-size N] [--eevee-cascades N] [--threads N]")
    if opts["engine"] not in ("cycles", "eevee"):
        die("--engine must be cycles or eevee, not %r" % opts["engine"])
    if opts["soft"] not in ("on", "off"):
        die("--eevee-soft-shadows must be on or off")
    sizes = ("512", "1024", "2048", "4096")
    for k, name in (("cube", "--eevee-cube-size"), ("cascade", "--eevee-cascade-size")):
        if str(opts[k]) not in sizes:
            die("%s must be one of %s" % (name, ", ".join(sizes)))
    for k, lo, hi in (("threads", 1, 1024), ("cascades", 1, 4)):
        try:
            opts[k] = int(opts[k])
        except ValueError:
            die("--%s must be an integer" % k)
        if not lo <= opts[k] <= hi:
            die("--%s must be in [%d, %d]" % (k, lo, hi))
    if opts["samples"] is None:
        opts["samples"] = 64 if opts["engine"] == "cycles" else 16
    try:
        opts["samples"] = int(opts["samples"])
    except ValueError:
        die("--samples must be an integer")
    if not 1 <= opts["samples"] <= 1 << 20:
        die("--samples must be in [1, 1048576]")
    return opts


# ---------------------------------------------------------------- view.json
def vec3(obj, key, where):
    v = obj.get(key)
    if not (isinstance(v, list) and len(v) == 3 and all(isinstance(x, (int, float)) for x in v)):
        die("%s: %s must be [x, y, z]" % (where, key))
    return [float(x) for x in v]


def number(obj, key, where, lo=None):
    v = obj.get(key)
    if not isinstance(v, (int, float)) or isinstance(v, bool):
        die("%s: %s must be a number" % (where, key))
    if lo is not None and not v > lo:
        die("%s: %s must be > %g" % (where, key, lo))
    return float(v)


def load_view(path):
    try:
        with open(path) as f:
            view = json.load(f)
    except OSError as e:
        die("cannot read %s: %s" % (path, e.strerror))
    except ValueError as e:
        die("%s is not JSON: %s" % (path, e))
    if not isinstance(view, dict) or view.get("view_format") != 1:
        die("%s: view_format must be 1" % path)
    for k in ("scene", "camera", "lights"):
        if k not in view:
            die("%s: no %s" % (path, k))
    if not isinstance(view["lights"], list) or not view["lights"]:
        die("%s: lights must be a non-empty array" % path)
    return view


def to_blender(p):
    """glTF / scene space (Y up) to Blender (Z up): (x, y, z) -> (x, -z, y). A rotation."""
    return Vector((p[0], -p[2], p[1]))


# ---------------------------------------------------------------- scene
def clear_scene():
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.lights, bpy.data.cameras, bpy.data.materials):
        for block in list(coll):
            coll.remove(block)


def import_geometry(view):
    geometry = view["scene"].get("geometry")
    if not isinstance(geometry, list):
        die("scene.geometry must be an array")
    meshes = []
    for gi, g in enumerate(geometry):
        where = "scene.geometry[%d]" % gi
        f = g.get("file")
        if not isinstance(f, str) or not os.path.isfile(f):
            die("%s: file %r does not exist" % (where, f))
        t = vec3(g, "translate", where) if "translate" in g else [0.0, 0.0, 0.0]
        s = g.get("scale", [1.0, 1.0, 1.0])
        if isinstance(s, (int, float)):
            s = [float(s)] * 3
        elif not (isinstance(s, list) and len(s) == 3):
            die("%s: scale must be a number or [sx, sy, sz]" % where)
        before = set(bpy.data.objects)
        # FLAT: geometric normals, as the oracle shades (docs/conventions.md).
        try:
            res = bpy.ops.import_scene.gltf(filepath=f, import_shading="FLAT")
        except ModuleNotFoundError as e:
            # Debian's blender package does not depend on python3-numpy, which the importer needs.
            die("Blender's glTF importer cannot run: %s (Debian: apt-get install python3-numpy)"
                % e, 3)
        except RuntimeError as e:
            die("%s: Blender's glTF importer failed on %s: %s"
                % (where, f, str(e).strip().splitlines()[-1]), 1)
        if "FINISHED" not in res:
            die("%s: Blender's glTF importer failed on %s" % (where, f), 1)
        new = [ob for ob in bpy.data.objects if ob not in before]
        # Scene space = scale then translate in glTF space. In Blender space that is
        # T(conv(t)) * conv * S * conv^-1 applied after the importer's own world matrix; glTF's y
        # scale lands on Blender's z and glTF's z scale on Blender's y.
        a = Matrix.Translation(to_blender(t)) @ Matrix.Diagonal((s[0], s[2], s[1], 1.0))
        for ob in new:
            if ob.type == "MESH":
                mw = ob.matrix_world.copy()
                meshes.append((ob, a @ mw))
        for ob in new:
            if ob.type != "MESH":
                bpy.data.objects.remove(ob, do_unlink=True)
    # Bake every transform into its own copy of the mesh data: a non-uniform scale over a rotated
    # node is a shear that an object's loc/rot/scale cannot hold.
    for ob, m in meshes:
        ob.parent = None
        ob.data = ob.data.copy()
        ob.data.transform(m)
        if m.determinant() < 0:
            ob.data.flip_normals()
        ob.matrix_world = Matrix.Identity(4)
    return [ob for ob, _ in meshes]


def white_lambert(objects):
    mat = bpy.data.materials.new("so_white_lambert")
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    bsdf = nt.nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.0
    nt.links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    for ob in objects:
        ob.data.materials.clear()
        ob.data.materials.append(mat)
        ob.active_material_index = 0
        for poly in ob.data.polygons:
            poly.material_index = 0


def place_camera(cam_json):
    where = "camera"
    eye = to_blender(vec3(cam_json, "eye", where))
    target = to_blender(vec3(cam_json, "target", where))
    up = to_blender(vec3(cam_json, "up", where))
    vfov = number(cam_json, "vfov_deg", where, 0.0)
    w, h = cam_json.get("width"), cam_json.get("height")
    if not (isinstance(w, int) and isinstance(h, int) and w > 0 and h > 0):
        die("camera: width and height must be positive integers")
    f = target - eye
    if f.length == 0:
        die("camera: eye and target are the same point")
    f.normalize()
    r = f.cross(up)
    if r.length < 1e-9:
        die("camera: up is parallel to the view direction")
    r.normalize()
    u = r.cross(f)
    # A Blender camera looks down its local -Z with +Y up.
    rot = Matrix((r, u, -f)).transposed()
    data = bpy.data.cameras.new("so_camera")
    data.type = "PERSP"
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(vfov)
    data.shift_x = data.shift_y = 0.0
    near = cam_json.get("near")
    far = cam_json.get("far")
    if isinstance(near, (int, float)) and near > 0:
        data.clip_start = float(near)
    if isinstance(far, (int, float)) and far > (near or 0):
        data.clip_end = float(far)
    ob = bpy.data.objects.new("so_camera", data)
    bpy.context.scene.collection.objects.link(ob)
    ob.matrix_world = Matrix.Translation(eye) @ rot.to_4x4()
    bpy.context.scene.camera = ob
    return w, h


def frame_from_z(z_axis, x_hint=None):
    """A rotation whose local Z is z_axis (unit); X along x_hint projected, if given."""
    z = z_axis.normalized()
    if x_hint is None or abs(x_hint.normalized().dot(z)) > 0.999:
        x_hint = Vector((1, 0, 0)) if abs(z.x) < 0.9 else Vector((0, 1, 0))
    x = (x_hint - z * x_hint.dot(z)).normalized()
    y = z.cross(x)
    return Matrix((x, y, z)).transposed().to_4x4()


def make_light(lj, engine, opts):
    """One Blender light object for a view.json light; returns (object, description)."""
    name = lj.get("name")
    typ = lj.get("type")
    where = "light %r" % name
    if not isinstance(name, str) or not name:
        die("a light has no name")
    ld = None
    mw = None
    if typ in ("point", "sphere"):
        ld = bpy.data.lights.new("so_" + name, "POINT")
        if typ == "point":
            p = vec3(lj, "position", where)
            ld.shadow_soft_size = 0.0
        else:
            p = vec3(lj, "center", where)
            ld.shadow_soft_size = number(lj, "radius", where, 0.0)
        mw = Matrix.Translation(to_blender(p))
    elif typ == "spot":
        p = vec3(lj, "position", where)
        d = to_blender(vec3(lj, "direction", where))
        outer = number(lj, "outer_cone_deg", where, 0.0)
        inner = float(lj.get("inner_cone_deg", 0.0))
        ld = bpy.data.lights.new("so_" + name, "SPOT")
        ld.shadow_soft_size = 0.0
        ld.spot_size = math.radians(2.0 * outer)  # Blender: the full cone angle
        ld.spot_blend = max(0.0, min(1.0, (outer - inner) / outer))  # intensity only, not V
        mw = Matrix.Translation(to_blender(p)) @ frame_from_z(-d)  # emits along local -Z
    elif typ == "directional":
        d = to_blender(vec3(lj, "direction", where))
        ld = bpy.data.lights.new("so_" + name, "SUN")
        ld.angle = 0.0
        mw = frame_from_z(-d)
    elif typ == "rect":
        c = to_blender(vec3(lj, "center", where))
        u = to_blender(vec3(lj, "u", where))
        v = to_blender(vec3(lj, "v", where))
        n = u.cross(v)
        if n.length == 0:
            die("%s: u and v are parallel" % where)
        if abs(u.normalized().dot(v.normalized())) > 1e-6:
            die("%s: u and v are not perpendicular; Blender's area light is a rectangle" % where)
        n.normalize()
        ld = bpy.data.lights.new("so_" + name, "AREA")
        ld.shape = "RECTANGLE"
        ld.size = u.length
        ld.size_y = v.length
        # A Blender area light emits along its local -Z: local Z = -n, local X = u. Then local Y =
        # Z x X = -(n x u), i.e. +-v: the rectangle is symmetric, so only the side matters.
        mw = Matrix.Translation(c) @ frame_from_z(-n, u)
    elif typ == "disk":
        c = to_blender(vec3(lj, "center", where))
        n = to_blender(vec3(lj, "normal", where))
        if n.length == 0:
            die("%s: normal is zero" % where)
        ld = bpy.data.lights.new("so_" + name, "AREA")
        ld.shape = "DISK"
        ld.size = 2.0 * number(lj, "radius", where, 0.0)
        mw = Matrix.Translation(c) @ frame_from_z(-n.normalized())
    else:
        die("%s: unknown type %r" % (where, typ))
    ld.color = (1.0, 1.0, 1.0)
    ld.energy = 1.0 if typ == "directional" else 100.0
    if ld.type == "AREA":
        ld.spread = math.pi
    ld.use_shadow = True
    if engine == "cycles":
        ld.cycles.use_multiple_importance_sampling = False  # pure light sampling
        ld.cycles.cast_shadow = True
        ld.cycles.max_bounces = 0
    else:
        ld.use_contact_shadow = False
        # EEVEE culls a light beyond the distance where its intensity falls under
        # scene.eevee.light_threshold: that would cut the unshadowed image too (V = 0 there).
        ld.use_custom_distance = True
        ld.cutoff_distance = 1.0e6
        if typ == "directional":
            ld.shadow_cascade_count = opts["cascades"]
    ob = bpy.data.objects.new("so_" + name, ld)
    ob.matrix_world = mw
    return ob


def set_render(engine, opts, w, h):
    scene = bpy.context.scene
    r = scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = w, h, 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.use_border = False
    r.film_transparent = False
    r.threads_mode = "FIXED"
    r.threads = opts["threads"]
    r.use_persistent_data = False
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    r.image_settings.color_mode = "RGB"
    r.image_settings.exr_codec = "NONE"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    world = bpy.data.worlds.new("so_black")
    world.use_nodes = True
    bg = world.node_tree.nodes.get("Background")
    bg.inputs["Color"].default_value = (0, 0, 0, 1)
    bg.inputs["Strength"].default_value = 0.0
    scene.world = world
    if engine == "cycles":
        r.engine = "CYCLES"
        c = scene.cycles
        c.device = "CPU"
        c.samples = opts["samples"]
        c.use_adaptive_sampling = False
        c.use_denoising = False
        c.light_sampling_threshold = 0.0
        c.sample_clamp_direct = 0.0
        c.sample_clamp_indirect = 0.0
        c.max_bounces = c.diffuse_bounces = c.glossy_bounces = 0
        c.transmission_bounces = c.volume_bounces = c.transparent_max_bounces = 0
        c.caustics_reflective = c.caustics_refractive = False
        c.pixel_filter_type = "GAUSSIAN"
        c.filter_width = 0.01  # samples the pixel centre (BOX is forced to width 1)
        c.seed = 0
        c.use_animated_seed = False
        if hasattr(c, "use_light_tree"):
            c.use_light_tree = False
        world.cycles_visibility.diffuse = False
    else:
        r.engine = "BLENDER_EEVEE"
        e = scene.eevee
        e.taa_render_samples = opts["samples"]
        e.use_soft_shadows = opts["soft"] == "on"
        e.shadow_cube_size = str(opts["cube"])
        e.shadow_cascade_size = str(opts["cascade"])
        e.use_gtao = e.use_ssr = e.use_bloom = e.use_motion_blur = e.use_volumetric_lights = False
        e.gi_diffuse_bounces = 0
        e.light_threshold = 0.0
        r.filter_size = 0.01  # EEVEE's film filter, in pixels: the pixel centre, as Cycles


# ---------------------------------------------------------------- render and read back
def render_to_pixels(path, w, h):
    scene = bpy.context.scene
    scene.render.filepath = path
    t0 = time.perf_counter()
    res = bpy.ops.render.render(write_still=True)
    ms = (time.perf_counter() - t0) * 1000.0
    if "FINISHED" not in res or not os.path.isfile(path):
        die("the render did not finish (%s)" % path, 1)
    img = bpy.data.images.load(path)
    if tuple(img.size) != (w, h):
        die("the render is %dx%d, expected %dx%d" % (img.size[0], img.size[1], w, h), 1)
    buf = array("f", [0.0]) * (w * h * 4)
    img.pixels.foreach_get(buf)
    bpy.data.images.remove(img)
    # Red channel (a white light on a white surface), rows flipped: Blender's row 0 is the bottom.
    out = array("f", [0.0]) * (w * h)
    for y in range(h):
        src = (h - 1 - y) * w * 4
        dst = y * w
        out[dst:dst + w] = buf[src:src + w * 4:4]
    return out, ms


def write_exr(path, w, h, channels):
    """Scanline OpenEXR 2.0, uncompressed, FLOAT channels (name -> array('f') top row first)."""
    names = sorted(channels)  # OpenEXR keeps the channel list sorted by name

    def attr(name, typ, data):
        return name.encode() + b"\0" + typ.encode() + b"\0" + struct.pack("<i", len(data)) + data

    chlist = b"".join(n.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for n in names)
    chlist += b"\0"
    box = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    header = b"".join([
        attr("channels", "chlist", chlist),
        attr("compression", "compression", b"\0"),
        attr("dataWindow", "box2i", box),
        attr("displayWindow", "box2i", box),
        attr("lineOrder", "lineOrder", b"\0"),
        attr("pixelAspectRatio", "float", struct.pack("<f", 1.0)),
        attr("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)),
        attr("screenWindowWidth", "float", struct.pack("<f", 1.0)),
        attr("shadowOracle/renderer", "string", b"blender render_shadows.py"),
    ]) + b"\0"
    head = struct.pack("<ii", 20000630, 2) + header
    line_bytes = 4 * w * len(names)
    first = len(head) + 8 * h
    offsets = struct.pack("<%dQ" % h, *[first + y * (8 + line_bytes) for y in range(h)])
    with open(path, "wb") as f:
        f.write(head)
        f.write(offsets)
        little = sys.byteorder == "little"
        for y in range(h):
            f.write(struct.pack("<ii", y, line_bytes))
            for n in names:
                row = channels[n][y * w:(y + 1) * w]
                if not little:
                    row = array("f", row)
                    row.byteswap()
                f.write(row.tobytes())


def main():
    opts = parse_args(sys.argv)
    view = load_view(opts["view"])
    engine = opts["engine"]
    names = [lj.get("name") for lj in view["lights"]]
    if len(set(names)) != len(names):
        die("light names are not unique")
    os.makedirs(opts["out"], exist_ok=True)
    effects = view["scene"].get("effects") or []
    if "alpha" in effects:
        sys.stderr.write("render_shadows.py: warning: the scene asks for alpha-tested materials; "
                         "every surface here is an opaque white Lambert, so they cast solid "
                         "shadows\n")

    clear_scene()
    objects = import_geometry(view)
    white_lambert(objects)
    w, h = place_camera(view["camera"])
    set_render(engine, opts, w, h)
    lights = [make_light(lj, engine, opts) for lj in view["lights"]]
    scene = bpy.context.scene

    tmp = tempfile.mkdtemp(prefix="so_blender_")
    channels = {}
    shadowed_ms = unshadowed_ms = 0.0
    per_light = {}
    for lj, lob in zip(view["lights"], lights):
        name = lj["name"]
        scene.collection.objects.link(lob)
        # Shadowed, then unshadowed with the same seed and samples (Cycles: the same light
        # samples, so the ratio's noise is the visibility's alone).
        for ob in objects:
            ob.visible_shadow = True
        lob.data.use_shadow = True
        lit, ms_s = render_to_pixels(os.path.join(tmp, name + "_shadowed.exr"), w, h)
        if engine == "cycles":
            for ob in objects:
                ob.visible_shadow = False
        else:
            lob.data.use_shadow = False
        ref, ms_u = render_to_pixels(os.path.join(tmp, name + "_unshadowed.exr"), w, h)
        scene.collection.objects.unlink(lob)
        peak = max(ref) if len(ref) else 0.0
        eps = peak * 1e-6
        vis = array("f", [0.0]) * (w * h)
        for k in range(w * h):
            u = ref[k]
            if u > eps and u > 0.0:
                x = lit[k] / u
                vis[k] = 0.0 if x < 0.0 else (1.0 if x > 1.0 else x)
        channels[name + ".V"] = vis
        shadowed_ms += ms_s
        unshadowed_ms += ms_u
        per_light[name] = {"shadowed_ms": round(ms_s, 3), "unshadowed_ms": round(ms_u, 3)}
        print("render_shadows.py: %s: shadowed %.0f ms, unshadowed %.0f ms" % (name, ms_s, ms_u))
        for suffix in ("_shadowed.exr", "_unshadowed.exr"):
            try:
                os.remove(os.path.join(tmp, name + suffix))
            except OSError:
                pass
    try:
        os.rmdir(tmp)
    except OSError:
        pass

    exr = os.path.join(opts["out"], "shadows.exr")
    write_exr(exr, w, h, channels)
    version = "%d.%d.%d" % bpy.app.version
    params = {"samples": opts["samples"], "threads": opts["threads"], "width": w, "height": h}
    if engine == "cycles":
        params.update({"pixel_filter": "gaussian", "filter_width": 0.01, "bounces": 0,
                       "mis": 0, "adaptive_sampling": 0, "denoising": 0})
    else:
        params.update({"soft_shadows": 1 if opts["soft"] == "on" else 0,
                       "shadow_cube_size": int(opts["cube"]),
                       "shadow_cascade_size": int(opts["cascade"]),
                       "shadow_cascade_count": opts["cascades"], "filter_size": 0.01})
    cost = {"renderer": "blender-%s %s" % (engine, version),
            "frame_ms": round(shadowed_ms, 3),
            "params": params}
    # Shadowed minus unshadowed: the time the shadows cost, where the difference is above the
    # noise of two renders (otherwise left out rather than reported as a number that means nothing).
    diff = shadowed_ms - unshadowed_ms
    if diff > 0.05 * shadowed_ms:
        cost["shadow_ms"] = round(diff, 3)
    with open(exr + ".json", "w") as f:
        json.dump(cost, f, indent=2)
        f.write("\n")
    with open(os.path.join(opts["out"], "render_times.json"), "w") as f:
        json.dump({"renderer": cost["renderer"], "lights": per_light}, f, indent=2)
        f.write("\n")
    print("render_shadows.py: wrote %s (%s) and %s.json" % (exr, ", ".join(sorted(channels)), exr))
    sys.stdout.flush()
    os._exit(0)


try:
    main()
except SystemExit:
    raise
except BaseException as e:  # one line, and a non-zero status (Blender's -P would exit 0)
    import traceback
    traceback.print_exc()
    die("%s: %s" % (type(e).__name__, e), 1)
