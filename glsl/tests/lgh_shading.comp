#version 450 core
// Test kernel: evaluates the GLSL blending functions and light contribution on given inputs.
layout(local_size_x = 64) in;
#include "shared/dispatch.glsl"
#include "shared/bindings.h"
#include "shared/lgh_shading.glsl"
#include "tests/test_types.h"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Cases { ShadingCase cases[]; };
layout(std430, binding = LGH_BINDING_PASS1) writeonly buffer Results { vec4 results[]; };  // rgb contribution, a blend

void main() {
  uint i = lghGlobalIndex();
  if (i >= uint(cases.length())) return;
  ShadingCase c = cases[i];
  vec3 l = lightContribution(c.lightPosOmni.xyz, c.intensityClamp.rgb, c.meanNormalD.xyz, c.lightPosOmni.w,
                             c.pointRadius.xyz, c.normalRole.xyz, c.intensityClamp.w);
  results[i] = vec4(l, blendWeight(uint(c.normalRole.w), c.meanNormalD.w, c.pointRadius.w));
}
