// Buffer and image binding points, one list for C++ and GLSL so a pass and its shader cannot disagree.
// (Macros, because layout(binding = ...) needs a constant expression on every GLSL compiler.)
#ifndef LGH_BINDINGS_H
#define LGH_BINDINGS_H

// Scene, bound once per frame (SSBOs).
#define LGH_BINDING_BVH_NODES 0
#define LGH_BINDING_BVH_TRIANGLES 1
#define LGH_BINDING_SCENE_TRIANGLES 2
#define LGH_BINDING_MATERIALS 3
#define LGH_BINDING_PUNCTUAL_LIGHTS 4
#define LGH_BINDING_TEXELS 5
#define LGH_BINDING_TEXTURE_INFOS 6
#define LGH_BINDING_SCENE_VERTICES 7

// Per-pass SSBOs start here.
#define LGH_BINDING_PASS0 8
#define LGH_BINDING_PASS1 9
#define LGH_BINDING_PASS2 10
#define LGH_BINDING_PASS3 11
#define LGH_BINDING_PASS4 12
#define LGH_BINDING_PASS5 13
#define LGH_BINDING_PASS6 14
#define LGH_BINDING_PASS7 15

// Uniform blocks.
#define LGH_UBO_FRAME 0
#define LGH_UBO_PASS 1

#endif
