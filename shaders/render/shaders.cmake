# Reference rendering (#4): the exact six-way baker and the volumetric path tracer.
list(APPEND SIXWAY_SHADERS
  render/light_depth.comp
  render/sixway_march.comp
  render/majorant.comp
  render/path_trace.comp
)
