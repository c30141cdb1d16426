#version 450 core
// Bounds of the lit lights (and of all lights, the fallback when none is lit), the largest light
// value (sets the fixed-point scale) and the number of lit lights. Work groups reduce in shared
// memory; one thread per group folds the result into global atomics on order-preserving float bits.
layout(local_size_x = 256) in;
#include "shared/dispatch.glsl"
#include "shared/lgh_grid.glsl"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = LGH_BINDING_PASS3) buffer Result { LghBoundsResult result; };
uniform uint lightCount;

shared vec3 litLo[256], litHi[256], allLo[256], allHi[256];
shared float largest[256];
shared uint litCount[256];

void main() {
  uint i = lghGlobalIndex(), t = gl_LocalInvocationID.x;
  const float inf = uintBitsToFloat(0x7f800000u);
  litLo[t] = vec3(inf); litHi[t] = vec3(-inf); allLo[t] = vec3(inf); allHi[t] = vec3(-inf);
  largest[t] = 0.0;
  litCount[t] = 0u;
  if (i < lightCount) {
    GpuLight light = lights[i];
    float a = luminance(light.intensity);
    allLo[t] = light.position;
    allHi[t] = light.position;
    if (a > 0.0) {
      litLo[t] = light.position;
      litHi[t] = light.position;
      largest[t] = max(a, max(light.intensity.r, max(light.intensity.g, light.intensity.b)));
      litCount[t] = 1u;
    }
  }
  barrier();
  for (uint stride = 128u; stride > 0u; stride >>= 1u) {
    if (t < stride) {
      litLo[t] = min(litLo[t], litLo[t + stride]);
      litHi[t] = max(litHi[t], litHi[t + stride]);
      allLo[t] = min(allLo[t], allLo[t + stride]);
      allHi[t] = max(allHi[t], allHi[t + stride]);
      largest[t] = max(largest[t], largest[t + stride]);
      litCount[t] += litCount[t + stride];
    }
    barrier();
  }
  if (t == 0u) {
    for (int axis = 0; axis < 3; ++axis) {
      atomicMin(result.litLower[axis], orderedBits(litLo[0][axis]));
      atomicMax(result.litUpper[axis], orderedBits(litHi[0][axis]));
      atomicMin(result.allLower[axis], orderedBits(allLo[0][axis]));
      atomicMax(result.allUpper[axis], orderedBits(allHi[0][axis]));
    }
    atomicMax(result.largestValue, orderedBits(largest[0]));
    atomicAdd(result.litCount, litCount[0]);
  }
}
