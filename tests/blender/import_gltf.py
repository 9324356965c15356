# Imports a .glb with Blender's own glTF importer and prints what Blender made of it, one
# "key: value" per line, for tests/blender/blender_gltf_test.sh.
#   blender --background --factory-startup --python-exit-code 1 --python import_gltf.py -- FILE.glb
import sys

import numpy as np

# Debian 12's Blender 3.4 glTF importer still calls np.bool, removed in numpy 1.24.
if "bool" not in np.__dict__:
    np.bool = bool

import bpy

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
result = bpy.ops.import_scene.gltf(filepath=path)
if "FINISHED" not in result:
    raise SystemExit("import failed: %s" % (result,))
meshes = [o for o in bpy.data.objects if o.type == "MESH"]
print("objects: %d" % len(meshes))
print("buildings_with_osm_id: %d" % sum(1 for o in meshes if str(o.get("osm_id", "")).startswith(("w", "r"))))
print("materials: %d" % len(bpy.data.materials))
print("triangles: %d" % sum(len(p.vertices) - 2 for o in meshes for p in o.data.polygons))
print("polygons_not_triangles: %d" % sum(1 for o in meshes for p in o.data.polygons if len(p.vertices) != 3))
# Blender is z-up again: the town stands on the ground, its tops above it.
zs = [(o.matrix_world @ v.co).z for o in meshes for v in o.data.vertices]
print("z_range: %.3f %.3f" % (min(zs), max(zs)))
print("first_osm_ids: %s" % ",".join(sorted(str(o["osm_id"]) for o in meshes if "osm_id" in o)[:3]))
