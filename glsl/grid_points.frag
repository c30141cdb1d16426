#version 450 core
// A round point with a dark rim, so it reads on bright and dark surfaces alike.
flat in vec4 pointColor;
layout(location = 0) out vec4 color;

void main() {
  vec2 d = gl_PointCoord * 2.0 - 1.0;
  float r2 = dot(d, d);
  if (r2 > 1.0) discard;
  color = vec4(r2 > 0.45 ? 0.15 * pointColor.rgb : pointColor.rgb, pointColor.a);
}
