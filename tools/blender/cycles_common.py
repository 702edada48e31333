# What cycles_lightmaps.py and cycles_scene.py share: sixway's medium, lights and sampling set up in Cycles with
# sixway's conventions (docs/blender.md, "The Cycles check"). Blender's coordinates are sixway's world
# coordinates, y up: nothing in a render depends on which way Blender calls up.
import math
import os
import sys

import bpy
from mathutils import Matrix, Vector


def fail(program, message):
    print(f"{program}: error: {message}", file=sys.stderr)
    sys.exit(1)


def run(program, main, source):
    """main(), with a malformed input (a missing key, a value of the wrong type) as one line naming the file
    source() gives."""
    try:
        main()
    except (KeyError, TypeError, ValueError, IndexError, AttributeError) as e:
        fail(program, f"{source()}: malformed ({type(e).__name__}: {e})")


def script_arguments():
    return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []


def _emission_nodes(nodes, links, emission):
    """intensity · density · ramp(temperature) (its Rec. 709 luminance with emission["luminance"]), and the
    math node input that holds the intensity."""
    keys = emission["ramp"]
    low, high = keys[0][0], keys[-1][0]
    temperature = nodes.new("ShaderNodeAttribute")
    temperature.attribute_name = emission["grid"]
    density = nodes.new("ShaderNodeAttribute")
    density.attribute_name = "density"
    # Color Ramp positions lie in [0, 1]: the temperatures are mapped there first (clamped, as sixway's ramp).
    to_unit = nodes.new("ShaderNodeMapRange")
    to_unit.clamp = True
    to_unit.inputs["From Min"].default_value, to_unit.inputs["From Max"].default_value = low, high
    links.new(temperature.outputs["Fac"], to_unit.inputs["Value"])
    ramp = nodes.new("ShaderNodeValToRGB")
    ramp.color_ramp.interpolation = "LINEAR"
    elements = ramp.color_ramp.elements
    while len(elements) < len(keys):
        elements.new(0.5)
    for element, (t, r, g, b) in zip(elements, keys):
        element.position, element.color = (t - low) / (high - low), (r, g, b, 1)
    links.new(to_unit.outputs["Result"], ramp.inputs["Fac"])
    colour = ramp.outputs["Color"]
    if emission["luminance"]:
        grey = nodes.new("ShaderNodeRGBToBW")  # the scene's luminance: Rec. 709 for linear sRGB
        links.new(colour, grey.inputs["Color"])
        combine = nodes.new("ShaderNodeCombineColor")
        for channel in ("Red", "Green", "Blue"):
            links.new(grey.outputs["Val"], combine.inputs[channel])
        colour = combine.outputs["Color"]
    gain = nodes.new("ShaderNodeMath")
    gain.operation = "MULTIPLY"
    links.new(density.outputs["Fac"], gain.inputs[0])
    gain.inputs[1].default_value = emission["intensity"]
    scaled = nodes.new("ShaderNodeVectorMath")
    scaled.operation = "SCALE"
    links.new(colour, scaled.inputs[0])
    links.new(gain.outputs["Value"], scaled.inputs["Scale"])
    return scaled.outputs["Vector"], gain.inputs[1]


def smoke_material(extinction, albedo, g, emission=None):
    """sixway's medium: σ_t = extinction · density, σ_s = albedo · σ_t, Henyey–Greenstein g (Principled
    Volume with a black Absorption Color: extinction = Density, scattering = Color · Density); emission: a
    dict with intensity, ramp ([temperature, r, g, b] keys), grid and luminance, or None. Returns the
    material, its volume node and the emission's intensity input (None without emission)."""
    material = bpy.data.materials.new("smoke")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    volume = nodes.new("ShaderNodeVolumePrincipled")
    volume.inputs["Density"].default_value = extinction
    volume.inputs["Color"].default_value = (albedo, albedo, albedo, 1)
    volume.inputs["Anisotropy"].default_value = g
    volume.inputs["Absorption Color"].default_value = (0, 0, 0, 1)
    volume.inputs["Blackbody Intensity"].default_value = 0
    links.new(volume.outputs["Volume"], out.inputs["Volume"])
    if not emission:
        return material, volume, None
    colour, intensity = _emission_nodes(nodes, links, emission)
    links.new(colour, volume.inputs["Emission Color"])
    volume.inputs["Emission Strength"].default_value = 1.0
    return material, volume, intensity


def volume_object(program, path, material, placement=Matrix.Identity(4), cell_size=None):
    """The VDB file `path` placed by `placement` (file space to world). Cycles samples voxel i at
    (i + 1/2) · dx, OpenVDB and sixway at i · dx: the grid is moved back half a voxel in file space. With
    `cell_size` (sixway's lattice cell, in file units), the file's voxels must be that size: sixway then
    rendered the file's own grid."""
    data = bpy.data.volumes.new("smoke")
    data.filepath = os.path.abspath(path)
    data.render.precision = "FULL"
    data.render.clipping = 0.0
    data.grids.load()
    density = data.grids.get("density")
    if density is None or not density.load():
        fail(program, f"{path}: Blender found no grid 'density' ({data.grids.error_message or 'no such grid'})")
    voxel = density.matrix_object.col[0].xyz.length
    if cell_size is not None and abs(voxel - cell_size) > 1e-4 * voxel:
        fail(program, f"{path}: sixway resampled it (cells of {cell_size:g}, voxels of {voxel:g}); bake with "
                      "--voxels native to compare the same grid")
    data.materials.append(material)
    obj = bpy.data.objects.new("smoke", data)
    half_voxel = -0.5 * (density.matrix_object.to_3x3() @ Vector((1, 1, 1)))
    obj.matrix_world = placement @ Matrix.Translation(half_voxel)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def sun(direction, irradiance=math.pi, colour=(1, 1, 1)):
    """A directional light from `direction` (toward the light) of that irradiance: Blender's sun strength."""
    data = bpy.data.lights.new("sun", "SUN")
    data.energy = irradiance
    data.color = colour
    data.angle = 0.0
    obj = bpy.data.objects.new("sun", data)
    # A sun shines along its local −z: its local +z points toward the light.
    obj.matrix_world = Vector((0, 0, 1)).rotation_difference(Vector(direction).normalized()).to_matrix().to_4x4()
    bpy.context.scene.collection.objects.link(obj)
    return obj


def point_light(position, intensity, colour=(1, 1, 1)):
    """A point light of radiant intensity `intensity` (W/sr): Cycles' point power P gives P / 4π (measured with
    a white Lambertian plane)."""
    data = bpy.data.lights.new("point", "POINT")
    data.energy = 4 * math.pi * intensity
    data.color = colour
    data.shadow_soft_size = 0.0
    obj = bpy.data.objects.new("point", data)
    obj.location = position
    bpy.context.scene.collection.objects.link(obj)
    return obj


def camera_object(position, right, up, forward):
    data = bpy.data.cameras.new("camera")
    data.type = "PERSP"
    data.clip_start, data.clip_end = 1e-4, 1e6
    obj = bpy.data.objects.new("camera", data)
    # Blender's camera looks down its local −z with +y up.
    rotation = Matrix((right, up, -Vector(forward))).transposed()
    obj.matrix_world = Matrix.Translation(Vector(position)) @ rotation.to_4x4()
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj
    return data


def configure(scene, width, height, spp, seed, step_rate, bounces, filter_width, threads=0, surface_bounces=0):
    """Cycles on the CPU, no adaptive sampling, denoising or clamping; `bounces` volume bounces (orders − 1),
    `surface_bounces` diffuse ones; a transparent film over a black world."""
    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = spp
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.seed = seed
    cycles.volume_step_rate = step_rate
    cycles.volume_max_steps = 100000
    cycles.volume_bounces = bounces
    cycles.max_bounces = max(bounces, surface_bounces, 1)
    cycles.diffuse_bounces = surface_bounces
    cycles.glossy_bounces = cycles.transmission_bounces = 0
    cycles.transparent_max_bounces = 64  # a shadow ray through the volume crosses its boundary mesh
    cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0
    cycles.light_sampling_threshold = 0.0
    cycles.filter_type = "BOX"
    cycles.filter_width = filter_width
    if threads:
        scene.render.threads_mode, scene.render.threads = "FIXED", threads
    scene.render.film_transparent = True
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.color_mode = "RGBA"
    scene.view_settings.view_transform = "Standard"
    world = bpy.data.worlds.new("black")
    world.use_nodes = False
    world.color = (0, 0, 0)
    scene.world = world


def uniform_environment(scene, radiance):
    """Radiance `radiance` (RGB) from every direction for scattered rays; camera rays see the transparent film."""
    world = bpy.data.worlds.new("ambient")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (*radiance, 1)
    background.inputs["Strength"].default_value = 1.0
    scene.world = world


def render(scene, path):
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
