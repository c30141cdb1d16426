#version 450 core
// Registers the vertices a level needs: every light (S0, or the grid lights of the level below for a
// gathered level) inserts the corners of its cell that get a non-zero trilinear weight.
layout(local_size_x = 256) in;
#include "shared/dispatch.glsl"
#include "shared/lgh_grid.glsl"

#ifdef LGH_FROM_GRID_LIGHTS
layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Sources { GpuGridLight sources[]; };
#else
layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Sources { GpuLight sources[]; };
#endif
layout(std430, binding = LGH_BINDING_PASS1) buffer TableKeys { uint tableKeys[]; };
layout(std430, binding = LGH_BINDING_PASS3) buffer Counters { uint counters[]; };  // [0] unique keys, [1] overflow
LGH_DEFINE_HASH_TABLE(table, tableKeys, counters, tableMask())
uniform uint sourceCount;

void main() {
  uint i = lghGlobalIndex();
  if (i >= sourceCount) return;
  // Level-count trials only need to know whether S1 reaches N/2 vertices: stop once it has.
  if (counters[0] >= grid.table.z) return;
  vec3 position = sources[i].position;
  if (!(luminance(sources[i].intensity) > 0.0)) return;
  GridCell c = locateCell(position);
  for (uint corner = 0u; corner < 8u; ++corner) {
    uvec3 offset = cornerOffset(corner);
    if (cornerWeight(c.t, offset) > 0.0) tableInsert(vertexKey(c.cell + offset));
  }
}
