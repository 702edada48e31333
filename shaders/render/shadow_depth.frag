#version 460
// Depth only: the shadow maps need no colour (the graphics pipeline takes a fragment stage).

void main() {}
