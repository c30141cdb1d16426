// The per-frame uniform block, bound once by the renderer at LGH_UBO_FRAME.
#ifndef LGH_FRAME_GLSL
#define LGH_FRAME_GLSL
#include "shared/bindings.h"
#include "shared/scene_types.h"
layout(std140, binding = LGH_UBO_FRAME) uniform Frame { FrameUniforms frame; };
#endif
