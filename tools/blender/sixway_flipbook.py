# A Blender add-on (and the same as a headless script) that makes a six-way flipbook from a smoke domain's
# OpenVDB cache with `sixway bake`: the textures in the packing chosen, Unity's .meta files and the sidecar
# (docs/blender.md, "Flipbooks from Blender").
#
# Add-on: Edit > Preferences > Add-ons > Install… this file; then Properties > Physics of a gas domain whose
# cache is OpenVDB and baked: "sixway flipbook".
# Headless:
#   blender -b SCENE.blend --python tools/blender/sixway_flipbook.py -- --out DIR [--domain NAME]
#       [--sixway PATH] [--frames FIRST LAST (default: the cache's)] [--tile N] [--packing unity|rlt-bbf|o3de]
#       [--camera scene|front] [--scattering multiple|single] [--emission X]
#       [--extinction X] [--albedo X] [--g X]
#
# The view is the scene camera's direction (or Blender's front view, −y looking +y, z up) carried into the
# cache's file space; the tile covers the smoke's billboard, as `sixway bake` frames it. The optics default
# to the domain's Principled Volume (Density → extinction, Color → albedo, Anisotropy → g), else sixway's.
# A domain with noise bakes the noise cache's finer density (without emission: that cache has no temperature);
# an adaptive domain is refused (its files do not say where its grid moved).
import argparse
import os
import shutil
import subprocess
import sys

import bpy
from mathutils import Matrix, Vector

bl_info = {
    "name": "sixway flipbook",
    "author": "sixway",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Physics (gas domain)",
    "description": "Six-way lightmap flipbooks of a smoke domain's cache, baked by sixway",
    "category": "Render",
}

PACKINGS = ("unity", "rlt-bbf", "o3de")


class FlipbookError(Exception):
    pass


def domain_settings(domain):
    for modifier in domain.modifiers:
        if modifier.type == "FLUID" and modifier.fluid_type == "DOMAIN":
            return modifier.domain_settings
    raise FlipbookError(f"'{domain.name}' is not a fluid domain")


def cache_files(domain, frames):
    """The cache's OpenVDB files of frames (first, last) (default: the cache's range), each one required."""
    settings = domain_settings(domain)
    if settings.domain_type != "GAS":
        raise FlipbookError(f"'{domain.name}' is a liquid domain; sixway bakes smoke")
    if settings.cache_data_format != "OPENVDB":
        raise FlipbookError(f"'{domain.name}': the cache's data format is {settings.cache_data_format}; "
                            "set it to OpenVDB and bake again")
    # An adaptive domain's files do not say where its moving grid lies (Blender keeps that in its own config
    # files): their file space is not the one below.
    if settings.use_adaptive_domain:
        raise FlipbookError(f"'{domain.name}' has an adaptive domain; turn it off and bake again")
    if settings.use_noise and settings.cache_noise_format != "OPENVDB":
        raise FlipbookError(f"'{domain.name}': the noise cache's format is {settings.cache_noise_format}; "
                            "set it to OpenVDB and bake the noise again")
    first, last = frames or (settings.cache_frame_start, settings.cache_frame_end)
    if first > last:
        raise FlipbookError(f"frames {first}..{last}: the first is after the last")
    # With noise, its finer grid (density_noise, in the same file space at 1/noise_scale the voxel size).
    folder, name = ("noise", "fluid_noise") if settings.use_noise else ("data", "fluid_data")
    cache = os.path.join(bpy.path.abspath(settings.cache_directory), folder)
    files = [os.path.join(cache, f"{name}_{frame:04d}.vdb") for frame in range(first, last + 1)]
    missing = [f for f in files if not os.path.isfile(f)]
    if missing:
        raise FlipbookError(f"{missing[0]}: no such cache file ({len(missing)} of frames {first}..{last} are "
                            f"missing; bake the domain's {folder} first)")
    return files


def to_file_space(domain):
    """Maps of points and directions from Blender's world into the cache's file space. Mantaflow writes the
    grids in world units from the domain's lower corner, unturned: world = M · (min_local + S⁻¹ · p), M the
    domain's matrix, S its scale, min_local its box's lower corner."""
    matrix = domain.matrix_world
    if matrix.is_negative:
        raise FlipbookError(f"'{domain.name}' is mirrored (a negative scale); Mantaflow's grid is not")
    _, _, scale = matrix.decompose()
    lower = Vector(min(corner[a] for corner in domain.bound_box) for a in range(3))
    try:
        inverse = matrix.inverted()
    except ValueError:
        raise FlipbookError(f"'{domain.name}' has a scale of 0") from None
    to_file = Matrix.Diagonal(scale).to_4x4() @ Matrix.Translation(-lower) @ inverse

    def point(p):
        return to_file @ Vector(p)

    def direction(d):
        return (to_file.to_3x3() @ Vector(d)).normalized()

    return point, direction


def camera_arguments(domain, camera):
    """--camera-position/target/up in the file space: `camera` an object, or None for the front view."""
    point, direction = to_file_space(domain)
    if camera is None:
        centre = domain.matrix_world @ (sum((Vector(c) for c in domain.bound_box), Vector()) / 8)
        size = max(domain.dimensions)
        position, forward, up = centre - Vector((0, 3 * size, 0)), Vector((0, 1, 0)), Vector((0, 0, 1))
    else:
        world = camera.matrix_world
        position = world.translation
        forward, up = -world.col[2].xyz, world.col[1].xyz
    p, f, u = point(position), direction(forward), direction(up)
    target = p + f
    return ["--camera-position", *map(str, p), "--camera-target", *map(str, target), "--camera-up", *map(str, u)]


def material_optics(domain):
    """Extinction, albedo and g of the domain's Principled Volume, as far as it has one."""
    optics = {}
    material = domain.active_material
    if material and material.use_nodes:
        for node in material.node_tree.nodes:
            if node.type == "PRINCIPLED_VOLUME":  # inputs driven by other nodes are left to sixway's defaults
                if not node.inputs["Density"].is_linked:
                    optics["extinction"] = node.inputs["Density"].default_value
                if not node.inputs["Color"].is_linked:
                    r, g, b, _ = node.inputs["Color"].default_value
                    optics["albedo"] = min(1.0, 0.2126 * r + 0.7152 * g + 0.0722 * b)
                if not node.inputs["Anisotropy"].is_linked:
                    optics["g"] = node.inputs["Anisotropy"].default_value
                break
    return optics


def find_sixway(given):
    path = given or os.environ.get("SIXWAY") or shutil.which("sixway")
    if not path or not os.path.isfile(path) or not os.access(path, os.X_OK):
        raise FlipbookError(f"no sixway executable ({given or 'SIXWAY, PATH'}); give its path")
    return path


def bake_command(domain, camera, out, sixway=None, frames=None, tile=128, packing="unity", scattering="multiple",
                 emission=0.0, optics=None):
    """The `sixway bake` command line for the domain's cache."""
    if packing not in PACKINGS:
        raise FlipbookError(f"packing must be one of {', '.join(PACKINGS)} (got {packing})")
    command = [find_sixway(sixway), "bake", "--vdb", *cache_files(domain, frames), "--voxels", "native",
               "--out", out, "--force", "--tile", str(tile), "--packing", packing, "--scattering", scattering]
    if domain_settings(domain).use_noise:
        if emission > 0:  # the noise upsamples the density and the flame, not the temperature that glows
            raise FlipbookError(f"'{domain.name}' adds noise, whose cache holds no temperature to glow: "
                                "bake with an emission of 0, or turn noise off")
        command += ["--density-grid", "density_noise"]
    command += camera_arguments(domain, camera)
    merged = {**material_optics(domain), **(optics or {})}
    for key in ("extinction", "albedo", "g"):
        if key in merged:
            command += [f"--{key}", repr(float(merged[key]))]
    if emission > 0:
        command += ["--emission", repr(float(emission))]
    return command


def bake(domain, camera, out, **options):
    """Runs the bake; raises FlipbookError with sixway's own error line when it fails."""
    command = bake_command(domain, camera, out, **options)
    try:
        done = subprocess.run(command, capture_output=True, text=True)
    except OSError as e:
        raise FlipbookError(f"{command[0]}: {e.strerror}") from None
    if done.returncode != 0:
        lines = [line for line in done.stderr.splitlines() if line.strip()]
        raise FlipbookError(lines[-1] if lines else f"sixway bake ended with {done.returncode}")
    return done.stdout


class SixwayFlipbookSettings(bpy.types.PropertyGroup):
    executable: bpy.props.StringProperty(name="sixway", subtype="FILE_PATH",
                                         description="The sixway executable (empty: SIXWAY, then PATH)")
    output: bpy.props.StringProperty(name="Output", subtype="DIR_PATH", default="//flipbook/")
    tile: bpy.props.IntProperty(name="Tile size", default=128, min=16, max=4096)
    packing: bpy.props.EnumProperty(name="Packing", items=[(p, p, "") for p in PACKINGS])
    camera: bpy.props.EnumProperty(name="View", items=[("scene", "Scene camera", ""),
                                                       ("front", "Front (Unity's exporter)", "")])
    scattering: bpy.props.EnumProperty(name="Scattering", items=[("multiple", "Multiple", ""),
                                                                 ("single", "Single", "")])
    emission: bpy.props.FloatProperty(name="Emission", default=0.0, min=0.0,
                                      description="Intensity of the temperature's glow (0: none)")


class SIXWAY_OT_bake_flipbook(bpy.types.Operator):
    bl_idname = "sixway.bake_flipbook"
    bl_label = "Bake six-way flipbook"
    bl_description = "Bake the domain's cache into six-way lightmap flipbooks with sixway"

    @classmethod
    def poll(cls, context):
        obj = context.object
        return obj is not None and any(m.type == "FLUID" and m.fluid_type == "DOMAIN" for m in obj.modifiers)

    def execute(self, context):
        s = context.scene.sixway_flipbook
        camera = context.scene.camera if s.camera == "scene" else None
        if s.camera == "scene" and camera is None:
            self.report({"ERROR"}, "the scene has no camera")
            return {"CANCELLED"}
        try:
            bake(context.object, camera, bpy.path.abspath(s.output), sixway=bpy.path.abspath(s.executable),
                 tile=s.tile, packing=s.packing, scattering=s.scattering, emission=s.emission)
        except FlipbookError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, f"six-way flipbook written to {bpy.path.abspath(s.output)}")
        return {"FINISHED"}


class SIXWAY_PT_flipbook(bpy.types.Panel):
    bl_label = "sixway flipbook"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "physics"

    @classmethod
    def poll(cls, context):
        return SIXWAY_OT_bake_flipbook.poll(context)

    def draw(self, context):
        s = context.scene.sixway_flipbook
        for name in ("executable", "output", "tile", "packing", "camera", "scattering", "emission"):
            self.layout.prop(s, name)
        self.layout.operator(SIXWAY_OT_bake_flipbook.bl_idname)


CLASSES = (SixwayFlipbookSettings, SIXWAY_OT_bake_flipbook, SIXWAY_PT_flipbook)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.sixway_flipbook = bpy.props.PointerProperty(type=SixwayFlipbookSettings)


def unregister():
    del bpy.types.Scene.sixway_flipbook
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)


def headless():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="sixway_flipbook.py")
    parser.add_argument("--out", required=True)
    parser.add_argument("--domain", help="the domain object (default: the only one)")
    parser.add_argument("--sixway", help="the sixway executable (default: SIXWAY, then PATH)")
    parser.add_argument("--frames", type=int, nargs=2, metavar=("FIRST", "LAST"))
    parser.add_argument("--tile", type=int, default=128)
    parser.add_argument("--packing", default="unity", choices=PACKINGS)
    parser.add_argument("--camera", default="scene", choices=("scene", "front"))
    parser.add_argument("--scattering", default="multiple", choices=("multiple", "single"))
    parser.add_argument("--emission", type=float, default=0.0)
    for key in ("extinction", "albedo", "g"):
        parser.add_argument(f"--{key}", type=float)
    args = parser.parse_args(argv)
    try:
        domains = [o for o in bpy.data.objects if o.type == "MESH" and
                   any(m.type == "FLUID" and m.fluid_type == "DOMAIN" for m in o.modifiers)]
        if args.domain:
            domains = [o for o in domains if o.name == args.domain]
        if len(domains) != 1:
            raise FlipbookError(f"{len(domains)} fluid domains match; name one with --domain")
        camera = bpy.context.scene.camera if args.camera == "scene" else None
        if args.camera == "scene" and camera is None:
            raise FlipbookError("the scene has no camera; give --camera front")
        optics = {k: getattr(args, k) for k in ("extinction", "albedo", "g") if getattr(args, k) is not None}
        print(bake(domains[0], camera, os.path.abspath(args.out), sixway=args.sixway, frames=args.frames,
                   tile=args.tile, packing=args.packing, scattering=args.scattering, emission=args.emission,
                   optics=optics), end="")
    except FlipbookError as e:
        print(f"sixway_flipbook: error: {e}", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    if bpy.app.background:
        headless()
    else:  # run from Blender's text editor: the add-on, for this session
        register()
