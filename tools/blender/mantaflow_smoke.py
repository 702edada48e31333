# Bakes a Mantaflow gas simulation headless from a JSON config and writes one OpenVDB file per frame
# (smoke_NNNN.vdb: grids density, temperature, flame, velocity, ... in Blender's z-up file space), for
# sixway's scene "vdb" section and `sixway bake --vdb` (docs/blender.md).
#
#   blender -b --factory-startup --python tools/blender/mantaflow_smoke.py -- CONFIG.json OUT_DIR [--blend]
#
# --blend also keeps the scene as OUT_DIR/scene.blend with its cache in OUT_DIR/cache (Blender's own layout),
# as a Blender user's smoke domain is (tools/blender/sixway_flipbook.py bakes from it).
#
# Config keys (metres, z up; unknown keys are errors):
#   resolution (64), frames (60)      cells along the domain's longest side; frames baked
#   domain_size ([2, 2, 3]), domain_centre (on the ground at the origin), scale_applied (true; false leaves
#       the size as the domain object's scale, as a Blender user's scaled cube)
#   density_buoyancy (1), heat_buoyancy (1), vorticity (0), time_scale (1), dissolve_frames (none)
#   burning_rate (0.75), flame_vorticity (0.5)
#   noise (0: none; 2-4): Blender's noise upres factor, baked into the cache's noise/ folder (OUT_DIR's VDB
#       files stay the base grid's)
#   emitters[] (required): shape (sphere | cube | cylinder), position, size, type (smoke | fire | both),
#       density (1), temperature (1), fuel (1), velocity (none), surface_distance (1.5), frames [first, last]
#   obstacles[]: shape, position, size, move_to (a straight path over the whole run)
#   wind: direction, strength (1), flow (0)
#   camera: position, target, fov_deg (40): the scene camera
#
# Flows and effectors are configured before the domain exists (Blender 3.4 breaks the next update when a
# flow's settings change after the domain is made).
import json
import math
import os
import shutil
import sys
import tempfile

import bpy
from mathutils import Vector

SHAPES = {"sphere", "cube", "cylinder"}
FLOW_TYPES = {"smoke": "SMOKE", "fire": "FIRE", "both": "BOTH"}


def fail(message):
    print(f"mantaflow_smoke: error: {message}", file=sys.stderr)
    sys.exit(1)


def vector(value, key, length=3):
    if not (isinstance(value, list) and len(value) == length and all(isinstance(v, (int, float)) for v in value)):
        fail(f"{key}: expected {length} numbers, got {value!r}")
    return [float(v) for v in value]


def number(config, key, default, low, high):
    value = config.get(key, default)
    if not isinstance(value, (int, float)) or not (low <= value <= high):
        fail(f"{key}: expected a number in [{low}, {high}], got {value!r}")
    return value


def add_shape(shape, position, size, name):
    if shape not in SHAPES:
        fail(f"{name}: shape must be one of {sorted(SHAPES)}, got {shape!r}")
    if shape == "sphere":
        bpy.ops.mesh.primitive_uv_sphere_add(radius=size / 2, location=position, segments=24, ring_count=12)
    elif shape == "cube":
        bpy.ops.mesh.primitive_cube_add(size=size, location=position)
    else:
        bpy.ops.mesh.primitive_cylinder_add(radius=size / 2, depth=size, location=position, vertices=24)
    obj = bpy.context.active_object
    obj.name = name
    return obj


def known_keys(entry, name, keys):
    """An object of the config with no key beyond `keys`."""
    if not isinstance(entry, dict):
        fail(f"{name}: expected an object, got {entry!r}")
    unknown = sorted(set(entry) - set(keys))
    if unknown:
        fail(f"{name}: unknown keys {unknown}")
    return entry


def add_emitter(index, emitter):
    known_keys(emitter, f"emitters[{index}]", ("shape", "position", "size", "type", "density", "temperature", "fuel",
                                               "velocity", "surface_distance", "frames"))
    obj = add_shape(emitter.get("shape", "sphere"), vector(emitter.get("position", [0, 0, 0]), "position"),
                    number(emitter, "size", 0.3, 0.01, 100), f"emitter{index}")
    flow = obj.modifiers.new("Fluid", "FLUID")
    flow.fluid_type = "FLOW"
    settings = flow.flow_settings
    kind = emitter.get("type", "smoke")
    if kind not in FLOW_TYPES:
        fail(f"emitters[{index}].type must be one of {sorted(FLOW_TYPES)}, got {kind!r}")
    settings.flow_type = FLOW_TYPES[kind]
    settings.flow_behavior = "INFLOW"
    settings.flow_source = "MESH"
    settings.surface_distance = number(emitter, "surface_distance", 1.5, 0, 10)
    settings.density = number(emitter, "density", 1.0, 0, 10)
    settings.temperature = number(emitter, "temperature", 1.0, -10, 10)
    if kind != "smoke":
        settings.fuel_amount = number(emitter, "fuel", 1.0, 0, 10)
    if "velocity" in emitter:
        settings.use_initial_velocity = True
        settings.velocity_coord = vector(emitter["velocity"], f"emitters[{index}].velocity")
    if "frames" in emitter:  # [first, last]: the flow emits over these frames only
        first, last = (int(f) for f in vector(emitter["frames"], f"emitters[{index}].frames", 2))
        for frame, on in ((first - 1, False), (first, True), (last + 1, False)):
            if frame >= 1:
                settings.use_inflow = on
                settings.keyframe_insert("use_inflow", frame=frame)
    obj.hide_render = True


def add_obstacle(index, obstacle):
    known_keys(obstacle, f"obstacles[{index}]", ("shape", "position", "size", "move_to"))
    start = vector(obstacle.get("position", [0, 0, 0]), f"obstacles[{index}].position")
    obj = add_shape(obstacle.get("shape", "sphere"), start, number(obstacle, "size", 0.5, 0.01, 100),
                    f"obstacle{index}")
    effector = obj.modifiers.new("Fluid", "FLUID")
    effector.fluid_type = "EFFECTOR"
    effector.effector_settings.effector_type = "COLLISION"
    if "move_to" in obstacle:  # a straight path over the whole run, at a constant speed
        obj.keyframe_insert("location", frame=1)
        obj.location = vector(obstacle["move_to"], f"obstacles[{index}].move_to")
        obj.keyframe_insert("location", frame=bpy.context.scene.frame_end)
        for curve in obj.animation_data.action.fcurves:
            for key in curve.keyframe_points:
                key.interpolation = "LINEAR"
    obj.hide_render = True


def add_wind(wind):
    known_keys(wind, "wind", ("direction", "strength", "flow"))
    direction = vector(wind.get("direction", [1, 0, 0]), "wind.direction")
    length = math.sqrt(sum(v * v for v in direction))
    if length == 0:
        fail("wind.direction: must not be zero")
    bpy.ops.object.effector_add(type="WIND", location=(0, 0, 0))
    field = bpy.context.active_object
    # A wind field blows along its local +z.
    field.rotation_mode = "QUATERNION"
    field.rotation_quaternion = Vector((0, 0, 1)).rotation_difference(Vector(direction) / length)
    field.field.strength = number(wind, "strength", 1.0, 0, 1000)
    field.field.flow = number(wind, "flow", 0.0, 0, 10)


def make_domain(config, cache):
    size = vector(config.get("domain_size", [2, 2, 3]), "domain_size")
    centre = vector(config.get("domain_centre", [0, 0, size[2] / 2]), "domain_centre")
    bpy.ops.mesh.primitive_cube_add(size=1, location=centre)
    domain = bpy.context.active_object
    domain.name = "domain"
    domain.scale = size
    if config.get("scale_applied", True):
        bpy.ops.object.transform_apply(location=False, rotation=False, scale=True)
    fluid = domain.modifiers.new("Fluid", "FLUID")
    fluid.fluid_type = "DOMAIN"
    settings = fluid.domain_settings
    settings.domain_type = "GAS"
    settings.resolution_max = int(number(config, "resolution", 64, 8, 512))
    settings.use_adaptive_domain = False
    settings.alpha = number(config, "density_buoyancy", 1.0, -10, 10)
    settings.beta = number(config, "heat_buoyancy", 1.0, -10, 10)
    settings.vorticity = number(config, "vorticity", 0.0, 0, 10)
    settings.time_scale = number(config, "time_scale", 1.0, 0.01, 10)
    settings.use_dissolve_smoke = "dissolve_frames" in config
    if settings.use_dissolve_smoke:
        settings.dissolve_speed = int(number(config, "dissolve_frames", 100, 1, 10000))
    settings.burning_rate = number(config, "burning_rate", 0.75, 0.01, 4)
    settings.flame_vorticity = number(config, "flame_vorticity", 0.5, 0, 2)
    noise = int(number(config, "noise", 0, 0, 4))
    if noise == 1:
        fail("noise: 0 (none) or an upres factor of 2 to 4")
    settings.use_noise = noise > 0
    if noise:
        settings.noise_scale = noise
        settings.cache_noise_format = "OPENVDB"
    settings.cache_directory = cache
    settings.cache_type = "ALL"
    settings.cache_data_format = "OPENVDB"
    settings.openvdb_data_depth = "32"
    settings.cache_frame_start = 1
    settings.cache_frame_end = bpy.context.scene.frame_end
    for boundary in ("use_collision_border_front", "use_collision_border_back", "use_collision_border_right",
                     "use_collision_border_left", "use_collision_border_top", "use_collision_border_bottom"):
        setattr(settings, boundary, False)  # open domain: smoke leaves through the faces
    return domain


def add_camera(camera):
    """The scene camera (for tools/blender/sixway_flipbook.py): position, target, fov_deg (vertical), z up."""
    known_keys(camera, "camera", ("position", "target", "fov_deg"))
    position = Vector(vector(camera.get("position"), "camera.position"))
    target = Vector(vector(camera.get("target"), "camera.target"))
    if (target - position).length == 0:
        fail("camera: target and position coincide")
    data = bpy.data.cameras.new("camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(number(camera, "fov_deg", 40, 1, 170))
    obj = bpy.data.objects.new("camera", data)
    obj.location = position
    obj.rotation_mode = "QUATERNION"
    obj.rotation_quaternion = (target - position).to_track_quat("-Z", "Y")
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    blend = "--blend" in argv
    argv = [a for a in argv if a != "--blend"]
    if len(argv) != 2:
        fail("usage: blender -b --factory-startup --python mantaflow_smoke.py -- CONFIG.json OUT_DIR [--blend]")
    return argv[0], argv[1], blend


def main():
    config_path, out_dir, keep_blend = arguments()
    try:
        with open(config_path) as f:
            config = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        fail(f"{config_path}: {e}")
    if not isinstance(config, dict):
        fail(f"{config_path}: not a JSON object")
    known = {"description", "resolution", "frames", "domain_size", "domain_centre", "density_buoyancy",
             "heat_buoyancy", "vorticity", "time_scale", "dissolve_frames", "burning_rate", "flame_vorticity",
             "emitters", "obstacles", "wind", "camera", "scale_applied", "noise"}
    unknown = sorted(set(config) - known)
    if unknown:
        fail(f"{config_path}: unknown keys {unknown}")
    if not isinstance(config.get("emitters"), list) or not config["emitters"]:
        fail(f"{config_path}: emitters: a non-empty list is required")
    if not isinstance(config.get("obstacles", []), list):
        fail(f"{config_path}: obstacles: must be a list")

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    frames = int(number(config, "frames", 60, 1, 10000))
    scene.frame_start, scene.frame_end = 1, frames
    for i, emitter in enumerate(config["emitters"]):
        add_emitter(i, emitter)
    for i, obstacle in enumerate(config.get("obstacles", [])):
        add_obstacle(i, obstacle)
    if "wind" in config:
        add_wind(config["wind"])
    if "camera" in config:
        add_camera(config["camera"])

    # Everything is made in OUT_DIR.partial and moved in whole at the end. With --blend the cache stays, as
    # cache/ beside scene.blend (a path relative to the .blend, so the folder can move). Mantaflow's noise
    # writes its wavelet tile (25 MB) into the working directory: a temporary one.
    out_dir, config_path = os.path.abspath(out_dir), os.path.abspath(config_path)
    scratch = tempfile.mkdtemp(prefix="mantaflow_")
    os.chdir(scratch)
    partial = out_dir.rstrip("/") + ".partial"
    shutil.rmtree(partial, ignore_errors=True)
    os.makedirs(partial)
    try:
        if keep_blend:
            bpy.context.preferences.filepaths.save_version = 0  # no scene.blend1 beside it
            bpy.ops.wm.save_as_mainfile(filepath=os.path.join(os.path.abspath(partial), "scene.blend"))
            cache = "//cache"
        else:
            cache = os.path.join(os.path.abspath(partial), "cache")
        domain = make_domain(config, cache)
        with bpy.context.temp_override(active_object=domain, object=domain, selected_objects=[domain]):
            result = bpy.ops.fluid.bake_all()
        if result != {"FINISHED"}:
            fail(f"Mantaflow bake ended with {result}")
        data = os.path.join(bpy.path.abspath(cache), "data")
        written = sorted((f for f in os.listdir(data) if f.startswith("fluid_data_") and f.endswith(".vdb")),
                         key=lambda name: int(name[len("fluid_data_"):-len(".vdb")]))
        if len(written) != frames:
            fail(f"Mantaflow wrote {len(written)} frames of {frames}")
        for i, name in enumerate(written):
            shutil.copyfile(os.path.join(data, name), os.path.join(partial, f"smoke_{i:04d}.vdb"))
        shutil.copyfile(config_path, os.path.join(partial, "mantaflow.json"))
        if keep_blend:
            bpy.ops.wm.save_mainfile()
        else:
            shutil.rmtree(bpy.path.abspath(cache))
        if os.path.isdir(out_dir):
            shutil.rmtree(out_dir)
        os.replace(partial, out_dir)
        print(f"mantaflow_smoke: wrote {frames} frames to {out_dir}")
    finally:
        shutil.rmtree(partial, ignore_errors=True)
        shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
