# Renders a citygen --export-ply file with Blender Cycles (CPU) for tests/bench/render_bench.sh.
#   blender -b --factory-startup -P tests/bench/cycles_render.py -- \
#       SCENE.ply OUT.png WIDTH HEIGHT SPP CAMERA(x,y,z) LOOK_AT(x,y,z) FOV_DEG SUN_DIR(x,y,z) SUN_IRRADIANCE THREADS
# Prints `cycles_render_seconds: S` (the render call: scene sync, BVH build and path tracing).
import math
import struct
import sys
import time

import bpy
import numpy as np
from mathutils import Vector

args = sys.argv[sys.argv.index("--") + 1:]
ply_path, out_path = args[0], args[1]
width, height, spp = int(args[2]), int(args[3]), int(args[4])
camera = Vector([float(v) for v in args[5].split(",")])
look_at = Vector([float(v) for v in args[6].split(",")])
fov_deg = float(args[7])
sun_dir = Vector([float(v) for v in args[8].split(",")])
sun_irradiance = float(args[9])
threads = int(args[10])


def read_ply(path):
    """Our binary PLY: float xyz vertices; faces = uchar 3, int32 x3, ushort material."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    materials, vertices, faces = [], 0, 0
    for line in header:
        words = line.split()
        if words[:2] == ["comment", "material"]:
            materials.append(dict(id=int(words[2]), name=words[3], type=words[4],
                                  albedo=[float(v) for v in words[5:8]],
                                  specular=[float(v) for v in words[8:11]],
                                  exponent=float(words[11]), ior=float(words[12])))
        elif words[:2] == ["element", "vertex"]:
            vertices = int(words[2])
        elif words[:2] == ["element", "face"]:
            faces = int(words[2])
    verts = np.frombuffer(data, dtype="<f4", count=3 * vertices, offset=end)
    face_type = np.dtype([("n", "u1"), ("v", "<i4", 3), ("m", "<u2")])
    face = np.frombuffer(data, dtype=face_type, count=faces, offset=end + 12 * vertices)
    return materials, verts, face["v"].ravel().astype(np.int32), face["m"].astype(np.int32)


def make_material(m):
    mat = bpy.data.materials.new(m["name"])
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    kind = m["type"]
    if kind == "glass":
        bsdf.inputs["Base Color"].default_value = (*m["specular"], 1)
        bsdf.inputs["Transmission"].default_value = 1.0
        bsdf.inputs["Roughness"].default_value = 0.0
        bsdf.inputs["IOR"].default_value = m["ior"]
    elif kind == "water":
        # A smooth dielectric over the water's body colour: F0 = 0.08 * Specular = 0.02.
        bsdf.inputs["Base Color"].default_value = (*m["albedo"], 1)
        bsdf.inputs["Roughness"].default_value = 0.0
        bsdf.inputs["Specular"].default_value = 0.25
    elif kind == "mirror":
        bsdf.inputs["Base Color"].default_value = (*m["specular"], 1)
        bsdf.inputs["Metallic"].default_value = 1.0
        bsdf.inputs["Roughness"].default_value = 0.0
    else:
        bsdf.inputs["Base Color"].default_value = (*m["albedo"], 1)
        if kind == "glossy":
            # Phong exponent n ~ Beckmann alpha sqrt(2/(n+2)); Blender roughness = sqrt(alpha).
            bsdf.inputs["Roughness"].default_value = (2 / (m["exponent"] + 2)) ** 0.25
            bsdf.inputs["Specular"].default_value = min(1.0, max(m["specular"]) / 0.08)
        else:
            bsdf.inputs["Roughness"].default_value = 1.0
            bsdf.inputs["Specular"].default_value = 0.0
    return mat


bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
materials, verts, loops, face_materials = read_ply(ply_path)

mesh = bpy.data.meshes.new("city")
mesh.vertices.add(len(verts) // 3)
mesh.vertices.foreach_set("co", verts)
mesh.loops.add(len(loops))
mesh.loops.foreach_set("vertex_index", loops)
faces = len(face_materials)
mesh.polygons.add(faces)
mesh.polygons.foreach_set("loop_start", np.arange(0, 3 * faces, 3, dtype=np.int32))
mesh.polygons.foreach_set("loop_total", np.full(faces, 3, dtype=np.int32))
for m in materials:
    mesh.materials.append(make_material(m))
mesh.polygons.foreach_set("material_index", face_materials)
mesh.update()
obj = bpy.data.objects.new("city", mesh)
scene.collection.objects.link(obj)

cam_data = bpy.data.cameras.new("camera")
cam_data.sensor_fit = "VERTICAL"
cam_data.angle_y = math.radians(fov_deg)
cam_data.clip_start = 0.1
cam_data.clip_end = 1e7
cam = bpy.data.objects.new("camera", cam_data)
cam.location = camera
cam.rotation_euler = (look_at - camera).to_track_quat("-Z", "Y").to_euler()
scene.collection.objects.link(cam)
scene.camera = cam

sun_data = bpy.data.lights.new("sun", "SUN")
sun_data.energy = sun_irradiance  # W/m^2: irradiance on a surface facing the sun
sun_data.angle = math.radians(0.53)
sun = bpy.data.objects.new("sun", sun_data)
sun.rotation_euler = sun_dir.to_track_quat("Z", "Y").to_euler()  # lights shine along -Z
scene.collection.objects.link(sun)

world = bpy.data.worlds.new("sky")
world.use_nodes = True
sky = world.node_tree.nodes.new("ShaderNodeTexSky")
sky.sky_type = "NISHITA"
sky.sun_disc = False
sky.sun_elevation = math.asin(max(-1.0, min(1.0, sun_dir.z)))
sky.sun_rotation = math.atan2(sun_dir.x, sun_dir.y)
world.node_tree.links.new(sky.outputs["Color"], world.node_tree.nodes["Background"].inputs["Color"])
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.06
scene.world = world

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = spp
scene.cycles.use_adaptive_sampling = False
scene.cycles.use_denoising = False
scene.cycles.max_bounces = 8
scene.cycles.diffuse_bounces = 8
scene.cycles.glossy_bounces = 8
scene.cycles.transmission_bounces = 8
scene.cycles.transparent_max_bounces = 8
scene.cycles.caustics_reflective = True
scene.cycles.caustics_refractive = True
scene.render.threads_mode = "FIXED"
scene.render.threads = threads
scene.render.resolution_x = width
scene.render.resolution_y = height
scene.render.resolution_percentage = 100
scene.render.image_settings.file_format = "PNG"
scene.render.filepath = out_path

start = time.time()
bpy.ops.render.render(write_still=True)
print("cycles_render_seconds: %.3f" % (time.time() - start))
print("cycles_triangles: %d" % faces)
