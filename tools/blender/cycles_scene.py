# Renders with Blender's Cycles the final image of a sixway scene as `sixway render --mode pathtrace` renders
# it: the smoke of a scene that plays OpenVDB files back (on the files' own voxels, "voxels": "native"), or of
# a simulated scene as `sixway sim --vdb-out` exported it (--vdb), with the scene's obstacles (opaque
# Lambertian, albedo 0.6; any shape, moving or still: the triangles `sim --vdb-out` wrote for that frame,
# --obstacles), perspective camera, directional and point lights,
# uniform ambient light and coloured emission (intensity · density · ramp(temperature)), every order of
# scattering (an obstacle's bounce counts as one, as in sixway's path tracer). Conventions: docs/blender.md,
# "The Cycles check"; here besides them:
#   - placement: world = translate + scale · U(p), U the scene's up turn; Blender's axes are sixway's;
#   - the camera: the vertical field of view, rays jittered over the pixel (box filter 1 px), as the path
#     tracer's;
#   - a point light of intensity I (W/sr): Cycles' point light of power 4π · I, radius 0;
#   - ambient: a uniform world of that radiance for scattered rays; the film is transparent, so the image is
#     the smoke's premultiplied radiance and alpha, to be put over the scene's background (cycles.json).
#
#   blender -b --factory-startup --python tools/blender/cycles_scene.py -- \
#       --scene SCENE.json --out DIR [--vdb EXPORTED.vdb [--obstacles EXPORTED.obj]] [--frame I] [--spp N] \
#       [--seed S] [--orders N]
#
# Writes DIR/cycles.exr (RGBA float, linear, premultiplied) and DIR/cycles.json. What the scene holds that
# this cannot render the same (camera or light paths, spherical-harmonic ambient, resampled voxels, a given
# box, another density grid; obstacles without --obstacles) is refused by name.
import argparse
import json
import math
import os
import sys
import time

import bpy
from mathutils import Matrix, Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles_common as cc  # noqa: E402

PROGRAM = "cycles_scene"


def arguments():
    parser = argparse.ArgumentParser(prog="cycles_scene.py")
    parser.add_argument("--scene", required=True, help="a sixway scene")
    parser.add_argument("--vdb", help="a simulated scene's smoke: the frame `sixway sim --vdb-out` wrote")
    parser.add_argument("--obstacles", help="the obstacles' triangles of that frame: the OBJ `sixway sim --vdb-out` "
                                            "wrote beside it (every shape, moving or still)")
    parser.add_argument("--out", required=True, help="output directory")
    parser.add_argument("--frame", type=int, default=0, help="the scene's frame (default 0)")
    parser.add_argument("--spp", type=int, default=256, help="samples per pixel (default 256)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--orders", type=int, default=64, help="scattering orders (default 64, as sixway's)")
    parser.add_argument("--step-rate", type=float, default=0.25,
                        help="Cycles' volume step rate, in voxels (default 0.25)")
    parser.add_argument("--threads", type=int, default=0, help="render threads (default: every core)")
    return parser.parse_args(cc.script_arguments())


def refuse(path, key, why):
    cc.fail(PROGRAM, f"{path}: {key}: {why}")


def vdb_file(path, scene, frame):
    vdb = scene["vdb"]
    base = os.path.dirname(os.path.abspath(path))
    if "files" in vdb:
        files = vdb["files"]
    else:
        files = [vdb["pattern"] % n for n in range(vdb["first"], vdb["last"] + 1)]
    per_file = vdb.get("frames_per_file", 1)
    if not 0 <= frame < len(files) * per_file:
        refuse(path, "--frame", f"{frame} is outside the scene's {len(files) * per_file} frames")
    return os.path.join(base, files[frame // per_file])


def placement(vdb):
    """File space to the scene's world: translate + scale · U(p)."""
    turn = Matrix.Identity(4)
    if vdb.get("up", "y") == "z":  # (x, y, z) → (x, z, −y)
        turn = Matrix(((1, 0, 0, 0), (0, 0, 1, 0), (0, -1, 0, 0), (0, 0, 0, 1)))
    scale = vdb.get("scale", 1.0)
    return Matrix.Translation(Vector(vdb.get("translate", [0, 0, 0]))) @ Matrix.Scale(scale, 4) @ turn


def check_supported(path, scene, exported, triangles):
    if scene.get("obstacles") and not triangles:
        refuse(path, "obstacles", "give their triangles (--obstacles: the OBJ `sixway sim --vdb-out` writes beside "
                                  "each frame of a simulated scene)")
    if triangles and not exported:
        refuse(path, "--obstacles", "goes with --vdb (the frame's triangles beside the frame's smoke)")
    vdb = scene.get("vdb")
    if vdb is None:
        if not exported:
            refuse(path, "vdb", "the scene simulates its smoke: give the frame sixway sim --vdb-out wrote (--vdb)")
        return
    if exported:
        refuse(path, "--vdb", "the scene plays its own VDB files back")
    if vdb.get("voxels") != "native":
        refuse(path, "vdb.voxels", 'must be "native": Cycles renders the files\' own voxels')
    for key in ("box_min", "box_max"):
        if key in vdb:
            refuse(path, f"vdb.{key}", "a given box resamples the files")
    if vdb.get("density_grid", "density") != "density":
        refuse(path, "vdb.density_grid", "only a grid named density")
    if "path" in scene.get("camera", {}):
        refuse(path, "camera.path", "a still camera only")
    for i, light in enumerate(scene.get("lights", [])):
        if "path" in light:
            refuse(path, f"lights[{i}].path", "still lights only")
    if "sh" in scene.get("ambient", {}):
        refuse(path, "ambient.sh", "a uniform ambient colour only")


def obstacle_material():
    """sixway's obstacles: opaque Lambertian, albedo 0.6 (render::kObstacleAlbedo)."""
    material = bpy.data.materials.new("obstacle")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.6, 0.6, 0.6, 1)
    out = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(diffuse.outputs["BSDF"], out.inputs["Surface"])
    return material


def import_obstacles(path):
    """The OBJ of `sixway sim --vdb-out` (render::placedObstacles, world coordinates) with its axes kept (sixway's
    are Blender's here) and its vertex normals as custom normals; every object gets the obstacles' material."""
    if not os.path.isfile(path):
        cc.fail(PROGRAM, f"{path}: no such file")
    before = set(bpy.data.objects)
    bpy.ops.wm.obj_import(filepath=path, forward_axis="Y", up_axis="Z")
    imported = [obj for obj in bpy.data.objects if obj not in before]
    if not imported:
        cc.fail(PROGRAM, f"{path}: no obstacle in the file")
    material = obstacle_material()
    for obj in imported:
        obj.data.materials.clear()
        obj.data.materials.append(material)


def scene_camera(camera, width, height):
    position, target = Vector(camera["position"]), Vector(camera["target"])
    forward = (target - position).normalized()
    right = forward.cross(Vector(camera.get("up", [0, 1, 0]))).normalized()
    up = right.cross(forward)
    data = cc.camera_object(position, right, up, forward)
    data.sensor_fit = "VERTICAL"
    data.sensor_height = 36.0
    data.angle_y = math.radians(camera.get("fov_deg", 40.0))


def main():
    args = arguments()
    try:
        with open(args.scene) as f:
            scene_json = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        cc.fail(PROGRAM, f"{args.scene}: {e}")
    if not isinstance(scene_json, dict):
        cc.fail(PROGRAM, f"{args.scene}: not a JSON object")
    check_supported(args.scene, scene_json, args.vdb, args.obstacles)
    # A simulation's export lies in the scene's world, voxel centres on the cell centres.
    vdb = scene_json.get("vdb", {"temperature_grid": "temperature"})
    path = vdb_file(args.scene, scene_json, args.frame) if "vdb" in scene_json else args.vdb
    render_settings = scene_json.get("render", {})
    width, height = render_settings.get("width", 256), render_settings.get("height", 256)

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    # An obstacle's bounce is an order too (path_trace.comp).
    cc.configure(scene, width, height, args.spp, args.seed, args.step_rate, args.orders - 1, 1.0, args.threads,
                 surface_bounces=args.orders - 1)
    scene_camera(scene_json["camera"], width, height)
    smoke = scene_json.get("smoke", {})
    emission = None
    if smoke.get("emission", {}).get("intensity", 0) > 0:
        if "temperature_grid" not in vdb:
            refuse(args.scene, "smoke.emission", "needs vdb.temperature_grid")
        ramp = [[key["temperature"], *key["color"]] for key in smoke["emission"]["ramp"]]
        # sixway scales the density itself by density_scale: the extinction and the emission alike.
        emission = {"intensity": smoke["emission"]["intensity"] * vdb.get("density_scale", 1.0), "ramp": ramp,
                    "grid": vdb["temperature_grid"], "luminance": False}
    extinction = smoke.get("extinction", 20.0) * vdb.get("density_scale", 1.0)
    material, _, _ = cc.smoke_material(extinction, smoke.get("albedo", 0.9), smoke.get("phase_g", 0.2), emission)
    cc.volume_object(PROGRAM, path, material, placement(vdb))
    if args.obstacles:
        import_obstacles(args.obstacles)
    for light in scene_json.get("lights", []):
        colour = light.get("color", [1, 1, 1])
        intensity = light.get("intensity", math.pi)
        if light["type"] == "directional":
            cc.sun(light["direction"], intensity, colour)
        else:
            cc.point_light(light["position"], intensity, colour)
    ambient = scene_json.get("ambient", {}).get("color")
    if ambient:
        cc.uniform_environment(scene, ambient)

    os.makedirs(args.out, exist_ok=True)
    start = time.time()
    cc.render(scene, os.path.join(args.out, "cycles.exr"))
    seconds = time.time() - start
    with open(os.path.join(args.out, "cycles.json"), "w") as f:
        json.dump({"scene": os.path.abspath(args.scene), "vdb": path, "frame": args.frame,
                   "background": render_settings.get("background", [0, 0, 0]), "samples_per_pixel": args.spp,
                   "seed": args.seed, "volume_bounces": args.orders - 1, "volume_step_rate": args.step_rate,
                   "render_seconds": round(seconds, 3), "blender": bpy.app.version_string}, f, indent=1)
    print(f"cycles_scene: {width}x{height}, {args.spp} spp: {seconds:.1f} s; wrote {args.out}/cycles.exr")


cc.run(PROGRAM, main, lambda: arguments().scene)
