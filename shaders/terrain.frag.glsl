#version 330 core
// Hillshaded terrain (light from the north-west, tinted by elevation) with one grid layer on top,
// coloured through a ramp. Cells below uEmptyBelow (dry) and cells without a value stay terrain.
in vec2 vCell;

uniform sampler2D uElevation;   // DEM [m], one texel per cell
uniform samplerBuffer uLayer;   // layer values, one float per cell, row-major (j * nx + i)
uniform sampler2D uRamp;        // 256 x 1 RGBA colour ramp
uniform bool uLayerOn;
uniform vec2 uRange;            // layer values mapped to the ends of the ramp
uniform float uEmptyBelow;      // values at or below are not drawn
uniform float uOpacity;         // of the layer over the terrain
uniform float uCellSize;        // dx [m]
uniform vec2 uElevationRange;   // min, max elevation [m], for the tint
uniform vec3 uLight;            // unit vector towards the light (x east, y north, z up)

out vec4 fragColor;

const float kNoData = -1e29;

float elevationAt(ivec2 c, float fallback) {
  ivec2 size = textureSize(uElevation, 0);
  if (c.x < 0 || c.y < 0 || c.x >= size.x || c.y >= size.y) return fallback;
  float z = texelFetch(uElevation, c, 0).r;
  return z > kNoData ? z : fallback;
}

void main() {
  ivec2 size = textureSize(uElevation, 0);
  ivec2 c = clamp(ivec2(floor(vCell)), ivec2(0), size - 1);
  float z = texelFetch(uElevation, c, 0).r;
  if (z <= kNoData) discard;
  // Central differences; j runs south, so north is j - 1.
  float zw = elevationAt(c + ivec2(-1, 0), z), ze = elevationAt(c + ivec2(1, 0), z);
  float zn = elevationAt(c + ivec2(0, -1), z), zs = elevationAt(c + ivec2(0, 1), z);
  vec3 normal = normalize(vec3(-(ze - zw) / (2.0 * uCellSize), -(zn - zs) / (2.0 * uCellSize), 1.0));
  float shade = max(dot(normal, uLight), 0.0);
  float height = clamp((z - uElevationRange.x) / max(uElevationRange.y - uElevationRange.x, 1e-6), 0.0, 1.0);
  vec3 tint = mix(vec3(0.56, 0.62, 0.47), vec3(0.88, 0.85, 0.80), height);
  vec3 color = tint * (0.2 + 0.8 * shade);
  if (uLayerOn) {
    float v = texelFetch(uLayer, c.y * size.x + c.x).r;
    if (v > kNoData && v > uEmptyBelow) {
      float t = clamp((v - uRange.x) / max(uRange.y - uRange.x, 1e-30), 0.0, 1.0);
      vec3 ramp = texture(uRamp, vec2(t, 0.5)).rgb;
      color = mix(color, ramp, uOpacity);
    }
  }
  fragColor = vec4(color, 1.0);
}
