#version 450
// Lambert under one directional light plus a little ambient, linear RGB, opaque.
layout(location = 0) in vec3 normal;
layout(location = 1) in vec3 albedo;
layout(location = 0) out vec4 color;

void main() {
  const vec3 toLight = normalize(vec3(0.3, 1.0, -0.2));
  color = vec4(albedo * (0.9 * max(dot(normalize(normal), toLight), 0.0) + 0.1), 1.0);
}
