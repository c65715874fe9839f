# Talus's Blender script (`talus render RUN_DIR`): the terrain as a shaded mesh, the run's VDB
# volume frames as a volume coloured by material, a camera framing the flow, a sun and a sky;
# one PNG per frame. `talus render` writes the JSON this reads and encodes the PNGs to an MP4.
# Everything is in the run's local frame: Blender keeps positions in single precision, so the
# volumes (in world coordinates) are moved by minus the local origin.
import array
import json
import math
import sys

import bpy
import mathutils

config = json.load(open(sys.argv[sys.argv.index("--") + 1]))
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
origin = mathutils.Vector(config["origin"])


def terrain():
    """The ground mesh: float32 heights (local frame, NaN outside the DEM) on a regular grid."""
    t = config.get("terrain")
    if not t:
        return
    z = array.array("f")
    with open(t["heights"], "rb") as f:
        z.frombytes(f.read())
    nx, ny, cell = t["nx"], t["ny"], t["cell"]
    verts = [(t["x0"] + c * cell, t["y0"] + r * cell, z[r * nx + c]) for r in range(ny) for c in range(nx)]
    ok = [v[2] == v[2] for v in verts]  # NaN is not equal to itself
    faces = []
    for r in range(ny - 1):
        for c in range(nx - 1):
            q = (r * nx + c, r * nx + c + 1, (r + 1) * nx + c + 1, (r + 1) * nx + c)
            if all(ok[k] for k in q):
                faces.append(q)
    verts = [v if v[2] == v[2] else (v[0], v[1], 0.0) for v in verts]
    mesh = bpy.data.meshes.new("ground")
    mesh.from_pydata(verts, [], faces)
    for poly in mesh.polygons:
        poly.use_smooth = True
    obj = bpy.data.objects.new("ground", mesh)
    scene.collection.objects.link(obj)
    mat = bpy.data.materials.new("ground")
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.22, 0.21, 0.19, 1)
    bsdf.inputs["Roughness"].default_value = 1.0
    bsdf.inputs["Specular"].default_value = 0.1
    mesh.materials.append(mat)


def volume_material():
    """Principled Volume: density from the `density` grid, colour mixed from the materials'
    volume fractions (each fraction times its colour, over their sum)."""
    mat = bpy.data.materials.new("flow")
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    pv = nodes.new("ShaderNodeVolumePrincipled")
    dens = nodes.new("ShaderNodeAttribute")
    dens.attribute_name = "density"
    scale = nodes.new("ShaderNodeMath")
    scale.operation = "MULTIPLY"
    scale.inputs[1].default_value = config["density_scale"]
    links.new(dens.outputs["Fac"], scale.inputs[0])
    links.new(scale.outputs["Value"], pv.inputs["Density"])
    colour, weight = None, None
    for name, rgb in config["materials"]:
        frac = nodes.new("ShaderNodeAttribute")
        frac.attribute_name = "fraction_" + name
        tint = nodes.new("ShaderNodeVectorMath")
        tint.operation = "SCALE"
        tint.inputs[0].default_value = rgb
        links.new(frac.outputs["Fac"], tint.inputs["Scale"])
        if colour is None:
            colour, weight = tint.outputs["Vector"], frac.outputs["Fac"]
            continue
        add = nodes.new("ShaderNodeVectorMath")
        add.operation = "ADD"
        links.new(colour, add.inputs[0])
        links.new(tint.outputs["Vector"], add.inputs[1])
        total = nodes.new("ShaderNodeMath")
        total.operation = "ADD"
        links.new(weight, total.inputs[0])
        links.new(frac.outputs["Fac"], total.inputs[1])
        colour, weight = add.outputs["Vector"], total.outputs["Value"]
    if colour is not None:
        guard = nodes.new("ShaderNodeMath")
        guard.operation = "MAXIMUM"
        guard.inputs[1].default_value = 1e-3
        links.new(weight, guard.inputs[0])
        inv = nodes.new("ShaderNodeMath")
        inv.operation = "DIVIDE"
        inv.inputs[0].default_value = 1.0
        links.new(guard.outputs["Value"], inv.inputs[1])
        mean = nodes.new("ShaderNodeVectorMath")
        mean.operation = "SCALE"
        links.new(colour, mean.inputs[0])
        links.new(inv.outputs["Value"], mean.inputs["Scale"])
        links.new(mean.outputs["Vector"], pv.inputs["Color"])
    links.new(pv.outputs["Volume"], out.inputs["Volume"])
    return mat


def camera_sun_sky():
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(cam)
    cam.data.lens = 35
    cam.data.clip_end = 1e5
    cam.location = mathutils.Vector(config["camera"])
    target = mathutils.Vector(config["target"])
    cam.rotation_euler = (target - cam.location).to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.energy = 2.5
    sun.data.angle = math.radians(2)
    sun.rotation_euler = (math.radians(40), 0, math.radians(140))  # from the south-west, 50 deg up
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    # A plain sky blue: Blender's Nishita sky rendered black headless here (3.4, Cycles on CPU).
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (0.45, 0.62, 0.85, 1)
    bg.inputs["Strength"].default_value = 0.6
    scene.world = world


def render_settings():
    r = scene.render
    r.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = config["samples"]
    scene.cycles.use_denoising = False  # Debian's Blender has no denoiser
    scene.cycles.volume_step_rate = 1.0
    r.resolution_x, r.resolution_y = config["width"], config["height"]
    r.resolution_percentage = 100
    r.image_settings.file_format = "PNG"
    r.film_transparent = False


terrain()
camera_sun_sky()
render_settings()
flow_mat = volume_material()
frames = config["frames"]
for i, (vdb, png) in enumerate(frames):
    vol = bpy.data.volumes.new("flow_%05d" % i)
    vol.filepath = vdb
    vol.grids.load()
    obj = bpy.data.objects.new("flow_%05d" % i, vol)
    obj.location = -origin
    vol.materials.append(flow_mat)
    scene.collection.objects.link(obj)
    scene.render.filepath = png
    bpy.ops.render.render(write_still=True)
    bpy.data.objects.remove(obj)
    bpy.data.volumes.remove(vol)
    print("TALUS frame %d %d" % (i + 1, len(frames)), flush=True)
