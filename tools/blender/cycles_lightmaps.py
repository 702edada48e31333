# Renders with Blender's Cycles the six-way lightmaps that `sixway bake --vdb` baked, from the bake's own
# sidecar (camera, billboard, optics, VDB file, scattering), so that the two can be compared texel by texel.
# Conventions matched (docs/blender.md, "The Cycles check"):
#   - the medium: Principled Volume, Density = extinction (σ_t per unit density), Color = albedo, Anisotropy
#     = g, Absorption Color black (σ_t = density, σ_s = color · density); emission = intensity · density ·
#     luminance(ramp(temperature)), the bake's own ramp;
#   - placement: the VDB file's space is the world (`bake --vdb` places it so); Cycles centres voxel i at
#     (i + 1/2) · dx where OpenVDB centres it at i · dx, so the volume object is moved by half a voxel;
#   - the camera: the bake's pinhole camera with its image plane cropped to the billboard, rays through the
#     pixel centres (box filter 0.01 px wide);
#   - each light channel: a sun of strength π (irradiance π, so a white Lambertian surface facing it is 1)
#     from the channel's direction in the camera's frame, black world; alpha = 1 − T (transparent film);
#     the emissive channel: no light, emission on (single scattering: a medium that scatters nothing);
#   - single scattering: no volume bounces; multiple: the bake's orders − 1 bounces.
#
#   blender -b --factory-startup --python tools/blender/cycles_lightmaps.py -- \
#       --flipbook BAKE/flipbook.json --out DIR [--spp N] [--seed S] [--frame I] [--step-rate R]
#
# Writes DIR/cycles_<Channel>.exr for Right, Left, Top, Bottom, Back, Front (and emissive, when the smoke
# emits): Blender's RGBA float EXR, linear, premultiplied, alpha = 1 − T; and DIR/cycles.json (the settings
# and the render time).
import argparse
import json
import os
import sys
import time

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles_common as cc  # noqa: E402

PROGRAM = "cycles_lightmaps"
CHANNELS = ["Right", "Left", "Top", "Bottom", "Back", "Front"]


def arguments():
    parser = argparse.ArgumentParser(prog="cycles_lightmaps.py")
    parser.add_argument("--flipbook", required=True, help="the bake's flipbook.json")
    parser.add_argument("--out", required=True, help="output directory")
    parser.add_argument("--spp", type=int, default=256, help="samples per pixel (default 256)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--frame", type=int, default=0, help="the bake's frame rendered (default 0)")
    parser.add_argument("--step-rate", type=float, default=0.25,
                        help="Cycles' volume step rate, in voxels (default 0.25)")
    parser.add_argument("--threads", type=int, default=0, help="render threads (default: every core)")
    return parser.parse_args(cc.script_arguments())


def read_bake(path, frame):
    try:
        with open(path) as f:
            sidecar = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        cc.fail(PROGRAM, f"{path}: {e}")
    p = sidecar.get("provenance", {})
    source = p.get("source", {})
    if "vdb" not in source or "scene" in source:
        cc.fail(PROGRAM, f"{path}: not a bake of VDB files (sixway bake --vdb; a scene places its files itself)")
    files = p["source"]["vdb"]
    if not 0 <= frame < len(p["frames"]):
        cc.fail(PROGRAM, f"{path}: --frame {frame}: the bake has frames 0..{len(p['frames']) - 1}")
    index = p["frames"][frame]["index"]
    layout = sidecar["layout"]
    return p, files[index], (layout["tile_width"], layout["tile_height"]), source["lattice"]["cell_size"]


def bake_camera(camera, billboard, width, height):
    """The bake's camera with its image plane cropped to the billboard."""
    right, up, forward = (Vector(camera[k]) for k in ("right", "up", "forward"))
    data = cc.camera_object(camera["position"], right, up, forward)
    lo, hi = Vector(billboard["image_plane_min"]), Vector(billboard["image_plane_max"])
    # The image plane at distance 1 spans hi − lo; Blender's frame spans sensor / lens along its larger side,
    # and shifts are in units of that side.
    span = hi - lo
    data.sensor_fit = "HORIZONTAL" if width >= height else "VERTICAL"
    data.sensor_width = data.sensor_height = 36.0
    larger = span.x if width >= height else span.y
    data.lens = 36.0 / larger
    centre = (lo + hi) / 2
    data.shift_x, data.shift_y = centre.x / larger, centre.y / larger
    return right, up, forward


def main():
    args = arguments()
    bake, vdb_path, (width, height), cell_size = read_bake(args.flipbook, args.frame)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scattering = bake["bake"]["scattering"]
    bounces = scattering.get("orders", 1) - 1 if scattering["mode"] == "multiple" else 0
    # Rays through the pixel centres, as the baker's.
    cc.configure(scene, width, height, args.spp, args.seed, args.step_rate, bounces, 0.01, args.threads)
    right, up, forward = bake_camera(bake["camera"], bake["billboard"], width, height)
    optics = bake["optics"]
    grid = bake["source"].get("temperature_grid")
    emission = None
    if optics["emission_intensity"] > 0 and grid and optics.get("emission_ramp"):
        emission = {"intensity": optics["emission_intensity"], "ramp": optics["emission_ramp"], "grid": grid,
                    "luminance": True}
    material, shader, emission_intensity = cc.smoke_material(optics["extinction"], optics["albedo"],
                                                             optics["phase_g"], emission)
    cc.volume_object(PROGRAM, vdb_path, material, cell_size=cell_size)
    directions = {"Right": right, "Left": -right, "Top": up, "Bottom": -up, "Back": forward, "Front": -forward}
    os.makedirs(args.out, exist_ok=True)
    start = time.time()
    if emission_intensity:
        emission_intensity.default_value = 0.0  # the light channels hold scattered light only
    for name in CHANNELS:
        light = cc.sun(directions[name])
        cc.render(scene, os.path.join(args.out, f"cycles_{name}.exr"))
        bpy.data.objects.remove(light)
    if emission_intensity:
        emission_intensity.default_value = emission["intensity"]
        if bounces == 0:
            # Direct emission only: with no volume bounces Cycles still gathers emission that scattered once
            # (measured: 1.8 times the direct emission on dense smoke), so the medium scatters nothing here
            # (Color black: σ_s = 0, σ_t unchanged with the black Absorption Color).
            shader.inputs["Color"].default_value = (0, 0, 0, 1)
        cc.render(scene, os.path.join(args.out, "cycles_emissive.exr"))
    seconds = time.time() - start
    with open(os.path.join(args.out, "cycles.json"), "w") as f:
        json.dump({"vdb": vdb_path, "samples_per_pixel": args.spp, "seed": args.seed,
                   "volume_step_rate": args.step_rate, "volume_bounces": bounces,
                   "render_seconds": round(seconds, 3), "blender": bpy.app.version_string}, f, indent=1)
    print(f"cycles_lightmaps: {width}x{height}, {args.spp} spp, {bounces} volume bounces: "
          f"{seconds:.1f} s; wrote {args.out}/cycles_*.exr")


cc.run(PROGRAM, main, lambda: arguments().flipbook)
