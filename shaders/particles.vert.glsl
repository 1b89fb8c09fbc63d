#version 330 core
// Particles as point sprites: world position [m] moved to the viewer's frame, one value each for the
// colour ramp.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in float aValue;

uniform mat4 uMvp;
uniform vec3 uOrigin;          // world x, y of the grid centre and the elevation drawn at z = 0 [m]
uniform float uExaggeration;   // as the terrain's
uniform float uPointSize;      // [pixels]
uniform vec2 uRange;           // values mapped to the ends of the ramp

out float vRampT;

void main() {
  vec3 p = vec3(aPosition.xy - uOrigin.xy, (aPosition.z - uOrigin.z) * uExaggeration);
  gl_Position = uMvp * vec4(p, 1.0);
  gl_PointSize = uPointSize;
  vRampT = clamp((aValue - uRange.x) / max(uRange.y - uRange.x, 1e-30), 0.0, 1.0);
}
