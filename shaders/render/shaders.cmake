# Reference rendering: the exact six-way baker and the volumetric path tracer.
list(APPEND SIXWAY_SHADERS
  render/light_depth.comp
  render/sixway_march.comp
  render/majorant.comp
  render/path_trace.comp
  render/obstacle.vert
  render/obstacle.frag
  render/shadow_depth.vert
  render/shadow_depth.frag
  render/billboard.vert
  render/sixway_shade.frag
  render/guide_march.comp
  render/motion_field.comp
  render/guide_lightmaps.comp
  render/repack_lightmaps.comp
  render/obstacle_ray_probe.comp
)
