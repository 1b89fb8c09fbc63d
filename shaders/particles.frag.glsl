#version 330 core
// Round point sprites with a dark rim, coloured through the ramp.
in float vRampT;

uniform sampler2D uRamp;   // 256 x 1 RGBA colour ramp

out vec4 fragColor;

void main() {
  vec2 d = gl_PointCoord * 2.0 - 1.0;
  float r2 = dot(d, d);
  if (r2 > 1.0) discard;
  vec3 color = texture(uRamp, vec2(vRampT, 0.5)).rgb;
  fragColor = vec4(r2 > 0.6 ? color * 0.45 : color, 1.0);
}
