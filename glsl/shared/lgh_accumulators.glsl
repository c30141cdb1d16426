// Per-vertex sums of a scattered level, 13 values per vertex in three arrays (so each stays under
// the shader storage block limit for twice as many vertices):
//   accPosition: D.xyz, Q.xyz   accIntensity: I.rgb   accNormal: N.xyz, O
// Default: 64-bit fixed point, added with two 32-bit atomics and an explicit carry. Integer sums are
// exact and order-independent, so thousands of lights on one vertex lose nothing (a float atomic sum
// stops growing once it is 2^24 times larger than the addend) and the build is deterministic.
// With LGH_FLOAT_ATOMICS (needs GL_NV_shader_atomic_float, enabled at the top of the kernel that
// adds, since #extension must precede all declarations): plain float atomicAdd, for comparison.
#ifndef LGH_ACCUMULATORS_GLSL
#define LGH_ACCUMULATORS_GLSL
#include "shared/bindings.h"

#ifdef LGH_FLOAT_ATOMICS
layout(std430, binding = LGH_BINDING_PASS4) buffer AccPosition { float accPosition[]; };
layout(std430, binding = LGH_BINDING_PASS5) buffer AccIntensity { float accIntensity[]; };
layout(std430, binding = LGH_BINDING_PASS6) buffer AccNormal { float accNormal[]; };
#define LGH_DEFINE_ACCUMULATOR(array)                                                      \
  void array##Add(uint index, float value) { atomicAdd(array[index], value); }             \
  float array##Read(uint index) { return array[index]; }
#else
layout(std430, binding = LGH_BINDING_PASS4) buffer AccPosition { uint accPosition[]; };
layout(std430, binding = LGH_BINDING_PASS5) buffer AccIntensity { uint accIntensity[]; };
layout(std430, binding = LGH_BINDING_PASS6) buffer AccNormal { uint accNormal[]; };
uniform float fixedPointScale;  // integer units per unit of value; |any sum| * scale < 2^62

// value * scale as a 64-bit two's complement (lo, hi). Small values convert through int; large ones
// split at 2^32, where both parts are exact because a float that large is a multiple of 2^8.
uvec2 toFixed(float value) {
  float v = value * fixedPointScale;
  if (abs(v) < 2147483648.0) {
    int i = int(round(v));
    return uvec2(uint(i), i < 0 ? 0xffffffffu : 0u);
  }
  float hi = floor(v * (1.0 / 4294967296.0));
  return uvec2(uint(v - hi * 4294967296.0), uint(int(hi)));
}
#define LGH_DEFINE_ACCUMULATOR(array)                                                      \
  void array##Add(uint index, float value) {                                               \
    uvec2 f = toFixed(value);                                                              \
    if (f == uvec2(0u)) return;                                                            \
    uint oldLo = atomicAdd(array[2u * index], f.x);                                        \
    uint hi = f.y + (oldLo + f.x < oldLo ? 1u : 0u); /* carry out of the low word */       \
    if (hi != 0u) atomicAdd(array[2u * index + 1u], hi);                                   \
  }                                                                                        \
  float array##Read(uint index) {                                                          \
    double v = double(int(array[2u * index + 1u])) * 4294967296.0 + double(array[2u * index]); \
    return float(v / double(fixedPointScale));                                             \
  }
#endif

LGH_DEFINE_ACCUMULATOR(accPosition)
LGH_DEFINE_ACCUMULATOR(accIntensity)
LGH_DEFINE_ACCUMULATOR(accNormal)

#endif
