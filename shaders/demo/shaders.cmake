# The interactive demo: its view of the frame pipeline's images.
list(APPEND SIXWAY_SHADERS
  demo/display.vert
  demo/display.frag
)
