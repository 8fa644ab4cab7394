"""What a Blender user gets from a subdfit result: each file imported by Blender's own importers
(the pinned bpy wheel) and rendered by Cycles beside the reference.

    python open_in_blender.py REFERENCE FILE[:MIN_PSNR] ... [--shots DIR]

REFERENCE is the dense source (OBJ or glTF), imported as Blender imports it. Each FILE is a
.glb (glTF importer) or a .usdz (USD importer, `import_subdivision=True` as docs/usd.md says).
Checks, per file: the import finishes; a glb's triangles are the file's; the file sits where the
reference sits (bounding box within 3 % of its diagonal: units and axes as Blender reads them);
its materials are the reference's kind (where the reference has none, only one that carries a
map, and texture coordinates only for an image; a base colour image where the reference reads
one); and two Cycles
renders match the reference's (PSNR over the pixels either covers >= MIN_PSNR, default 28 dB).
Prints one line a file; exits 1 on the first file that fails, naming it and what.
"""
import json
import math
import os
import struct
import sys

import bpy
import numpy as np
from mathutils import Vector

SIZE = 128
VIEWS = [Vector((1.2, -2.0, 0.8)), Vector((-1.5, 1.6, 0.3))]  # front-left above, back-right level


def fail(path, what):
    print(f"{path}: {what}")
    sys.exit(1)


def fresh_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)


def import_file(path):
    """The mesh objects Blender's importer for `path` makes, in a fresh scene."""
    fresh_scene()
    extension = os.path.splitext(path)[1].lower()
    importers = {".obj": lambda: bpy.ops.wm.obj_import(filepath=path),
                 ".glb": lambda: bpy.ops.import_scene.gltf(filepath=path),
                 ".gltf": lambda: bpy.ops.import_scene.gltf(filepath=path),
                 ".usdz": lambda: bpy.ops.wm.usd_import(filepath=path, import_subdivision=True)}
    if extension not in importers:
        fail(path, "no Blender importer for this extension")
    try:
        result = importers[extension]()
    except RuntimeError as error:  # the importer's report, e.g. an extension it does not read
        fail(path, "Blender's importer refused it: " + " ".join(str(error).split()))
    if result != {"FINISHED"}:
        fail(path, f"import returned {result}")
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    if not meshes:
        fail(path, "no mesh imported")
    return meshes


def bounds(objects):
    corners = [o.matrix_world @ Vector(c) for o in objects for c in o.bound_box]
    lo = Vector(tuple(min(p[i] for p in corners) for i in range(3)))
    hi = Vector(tuple(max(p[i] for p in corners) for i in range(3)))
    return lo, hi


def glb_triangles(path):
    """Triangles the glb's primitives index (mode 4), read from its JSON chunk."""
    with open(path, "rb") as f:
        data = f.read()
    length, kind = struct.unpack_from("<II", data, 12)
    if kind != 0x4E4F534A:
        fail(path, "not a glb: its first chunk is not JSON")
    doc = json.loads(data[20:20 + length])
    return sum(doc["accessors"][p["indices"]]["count"] // 3
               for m in doc["meshes"] for p in m["primitives"] if p.get("mode", 4) == 4)


def base_colour_images(objects):
    """Images linked (through any nodes) into a Principled BSDF's Base Color, per object."""
    images = []
    for o in objects:
        for material in o.data.materials:
            if material is None or material.node_tree is None:
                continue
            for node in material.node_tree.nodes:
                if node.type != "BSDF_PRINCIPLED":
                    continue
                stack = [link.from_node for link in node.inputs["Base Color"].links]
                while stack:
                    upstream = stack.pop()
                    if upstream.type == "TEX_IMAGE" and upstream.image is not None:
                        images.append(upstream.image)
                    stack += [link.from_node for socket in upstream.inputs for link in socket.links]
    return images


def materials(objects):
    return [m for o in objects for m in o.data.materials if m is not None]


def reads_an_image(material):
    return material.node_tree is not None and any(n.type == "TEX_IMAGE" for n in material.node_tree.nodes)


def render(objects, frame, path_png):
    """Cycles renders of the scene from VIEWS around `frame` (the reference's bounds): RGBA arrays."""
    scene = bpy.context.scene
    lo, hi = frame
    centre, radius = (lo + hi) / 2, (hi - lo).length / 2
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.data.clip_start, camera.data.clip_end = radius * 0.01, radius * 100
    scene.collection.objects.link(camera)
    scene.camera = camera
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (0.6, 0.2, 0.8)
    scene.collection.objects.link(sun)
    scene.world = bpy.data.worlds.new("world")
    scene.world.color = (0.5, 0.5, 0.5)
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 32
    scene.cycles.seed = 1
    scene.cycles.use_denoising = False
    scene.render.film_transparent = True
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    shots = []
    for i, direction in enumerate(VIEWS):
        camera.location = centre + direction.normalized() * radius * 2.6
        camera.rotation_euler = (centre - camera.location).to_track_quat("-Z", "Y").to_euler()
        scene.render.filepath = f"{path_png}_{i}.png"
        bpy.ops.render.render(write_still=True)
        image = bpy.data.images.load(scene.render.filepath)
        shots.append(np.array(image.pixels[:], dtype=np.float64).reshape(SIZE, SIZE, 4))
    return shots


def psnr(a, b):
    """PSNR of the premultiplied colours over the pixels either render covers."""
    covered = (a[..., 3] > 0) | (b[..., 3] > 0)
    if not covered.any():
        return 0.0
    pa, pb = a[..., :3] * a[..., 3:], b[..., :3] * b[..., 3:]
    mse = ((pa - pb) ** 2)[covered].mean()
    return 99.0 if mse == 0 else 10 * math.log10(1.0 / mse)


def main():
    args = sys.argv[1:]
    shots_dir = None
    if "--shots" in args:
        i = args.index("--shots")
        shots_dir = args[i + 1]
        del args[i:i + 2]
    if len(args) < 2:
        print(__doc__)
        sys.exit(2)
    reference, files = args[0], args[1:]
    shots_dir = shots_dir or os.path.join(os.path.dirname(os.path.abspath(files[0])), "blender")
    os.makedirs(shots_dir, exist_ok=True)
    bpy.context.preferences.view.show_splash = False

    objects = import_file(reference)
    frame = bounds(objects)
    diagonal = (frame[1] - frame[0]).length
    reference_images = base_colour_images(objects)
    reference_materials = len(materials(objects))
    reference_shots = render(objects, frame, os.path.join(shots_dir, "reference"))

    for entry in files:
        path, _, minimum = entry.partition(":")
        minimum = float(minimum or 28.0)
        objects = import_file(path)
        name = os.path.basename(path).replace(".", "_")
        if path.endswith(".glb"):
            triangles = sum(len(o.data.polygons) for o in objects)
            if triangles != glb_triangles(path):
                fail(path, f"{triangles} faces in Blender, {glb_triangles(path)} triangles in the file")
        else:
            if not all(any(m.type == "SUBSURF" and m.subdivision_type == "CATMULL_CLARK" for m in o.modifiers)
                       for o in objects):
                fail(path, "not imported as a Catmull-Clark subdivision surface")
        lo, hi = bounds(objects)
        offset = max((lo - frame[0]).length, (hi - frame[1]).length)
        if offset > 0.03 * diagonal:
            fail(path, f"its bounds {tuple(lo)}..{tuple(hi)} are not the reference's "
                       f"{tuple(frame[0])}..{tuple(frame[1])}")
        images = base_colour_images(objects)
        if reference_images and not images:
            fail(path, "no base colour image, where the reference reads one")
        if not reference_images and images:
            fail(path, "a base colour image, where the reference reads none")
        invented = [m for m in materials(objects) if not reads_an_image(m)]
        if reference_materials == 0 and invented:
            fail(path, f"material {invented[0].name!r} reads no image, where the reference has no material")
        reading = any(reads_an_image(m) for m in materials(objects))
        if not reading and path.endswith(".glb") and any(len(o.data.uv_layers) for o in objects):
            fail(path, "texture coordinates that no image reads")
        if any(min(image.size) == 0 for image in images):
            fail(path, "a base colour image Blender could not read")
        shots = render(objects, frame, os.path.join(shots_dir, name))
        scores = [psnr(a, b) for a, b in zip(reference_shots, shots)]
        if min(scores) < minimum:
            fail(path, f"renders {min(scores):.2f} dB from the reference in Cycles (at least {minimum} expected; "
                       f"renders in {shots_dir})")
        print(f"{path}: opens in Blender {bpy.app.version_string}, {len(images)} base colour image(s), "
              f"{len(materials(objects))} material(s), Cycles {', '.join(f'{s:.2f}' for s in scores)} dB")


if __name__ == "__main__":
    main()
