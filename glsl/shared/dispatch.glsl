// Include after the layout(local_size...) declaration (gl_WorkGroupSize needs it).
// Flat invocation index for 1-D work folded into 2-D dispatches (Program::dispatch1D), which keeps
// every dimension under the 65535-group limit for any light count.
#ifndef LGH_DISPATCH_GLSL
#define LGH_DISPATCH_GLSL
uint lghGlobalIndex() {
  return gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x);
}
#endif
