"""Blender (run as `blender -b -P render_obj.py -- model.obj picture.png`):
a picture of what an OBJ holds, in its material colours, from the south-west
and above, framing everything. Used to look at what web-ifc read from a castor
IFC file (benchmarks/webifc_read.js); OBJ is +Y up, Blender's importer turns
it to Blender's +Z up."""

import math
import sys

import bpy
from mathutils import Vector

model, picture = sys.argv[sys.argv.index("--") + 1:][:2]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.obj(filepath=model)
meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
corners = [o.matrix_world @ Vector(c) for o in meshes for c in o.bound_box]
low = Vector([min(c[i] for c in corners) for i in range(3)])
high = Vector([max(c[i] for c in corners) for i in range(3)])
centre, size = (low + high) / 2, (high - low).length
scene = bpy.context.scene
camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
scene.collection.objects.link(camera)
scene.camera = camera
azimuth, elevation = math.radians(-60), math.radians(25)
direction = Vector((math.cos(elevation) * math.cos(azimuth),
                    math.cos(elevation) * math.sin(azimuth), math.sin(elevation)))
camera.location = centre + direction * size * 1.25
camera.rotation_euler = (centre - camera.location).to_track_quat("-Z", "Y").to_euler()
camera.data.lens = 35
scene.render.engine = "BLENDER_WORKBENCH"
scene.display.shading.light = "STUDIO"
scene.display.shading.color_type = "MATERIAL"
scene.display.shading.show_cavity = False
scene.display.shading.show_object_outline = True
scene.render.resolution_x, scene.render.resolution_y = 1000, 750
scene.render.film_transparent = False
scene.render.filepath = picture
bpy.ops.render.render(write_still=True)
