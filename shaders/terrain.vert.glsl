#version 330 core
// Terrain mesh: vertices at cell corners in cell units (i east, j south), lifted by the DEM in the
// tilted 3D view (uExaggeration > 0) and flat in the map view (uExaggeration = 0).
layout(location = 0) in vec2 aCorner;

uniform sampler2D uElevation;   // DEM [m], one texel per cell, kNoData outside the domain
uniform vec2 uGridSize;         // nx, ny
uniform float uCellSize;        // dx [m]
uniform float uElevationMid;    // elevation drawn at z = 0 [m]
uniform float uExaggeration;    // vertical exaggeration
uniform mat4 uMvp;

out vec2 vCell;                 // position in cell units, for the fragment shader

const float kNoData = -1e29;

// Elevation at a cell corner: the mean of the valid cells around it.
float cornerElevation(vec2 corner) {
  ivec2 size = textureSize(uElevation, 0);
  float sum = 0.0;
  float n = 0.0;
  for (int dj = -1; dj <= 0; ++dj)
    for (int di = -1; di <= 0; ++di) {
      ivec2 c = clamp(ivec2(corner) + ivec2(di, dj), ivec2(0), size - 1);
      float z = texelFetch(uElevation, c, 0).r;
      if (z > kNoData) { sum += z; n += 1.0; }
    }
  return n > 0.0 ? sum / n : uElevationMid;
}

void main() {
  vCell = aCorner;
  float z = uExaggeration > 0.0 ? cornerElevation(aCorner) : uElevationMid;
  vec3 p = vec3((aCorner.x - 0.5 * uGridSize.x) * uCellSize, (0.5 * uGridSize.y - aCorner.y) * uCellSize,
                (z - uElevationMid) * uExaggeration);
  gl_Position = uMvp * vec4(p, 1.0);
}
