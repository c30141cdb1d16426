#version 450 core
// Test kernel: values[i] = values[i] * factor + i, for the context and dispatch tests.
layout(local_size_x = 64) in;
#include "shared/bindings.h"
#include "shared/dispatch.glsl"
layout(std430, binding = LGH_BINDING_PASS0) buffer Values { float values[]; };
uniform float factor;
uniform uint count;
void main() {
  uint i = lghGlobalIndex();
  if (i >= count) return;
  values[i] = values[i] * factor + float(i);
}
