// Buffer and image binding points, one list for C++ and GLSL so a pass and its shader cannot disagree.
// (Macros, because layout(binding = ...) needs a constant expression on every GLSL compiler.)
#ifndef LGH_BINDINGS_H
#define LGH_BINDINGS_H

// Scene, bound once per frame (SSBOs; 0 and 1 unused).
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

// Texture units. A pass that reads the G-buffer (shared/gbuffer.glsl) has it on units 0-3; the
// light pass reads its surfaces (the G-buffer or its interleaved tiles) on the same first two.
#define LGH_TEXTURE_GBUFFER_POSITION 0
#define LGH_TEXTURE_GBUFFER_NORMAL 1
#define LGH_TEXTURE_GBUFFER_ALBEDO 2
#define LGH_TEXTURE_GBUFFER_EMISSION 3
#define LGH_TEXTURE_SURFACE_POSITION 0
#define LGH_TEXTURE_SURFACE_NORMAL 1
#define LGH_TEXTURE_SURFACE_DEPTH_PYRAMID 2  // light pass: max depth of the surfaces per tile (volume culling)
// G-buffer pass: the material's textures while drawing.
#define LGH_TEXTURE_MATERIAL_BASE_COLOR 0
#define LGH_TEXTURE_MATERIAL_EMISSIVE 1
// Passes that also read the G-buffer take their own inputs from unit 4 on.
#define LGH_TEXTURE_TILED_IRRADIANCE 4       // interleave resolve
#define LGH_TEXTURE_TILED_FRAGMENT_COUNTS 5  // interleave resolve
#define LGH_TEXTURE_SHADOW_IRRADIANCE 4      // shadow rays: the light pass's irradiance, in its layout
#define LGH_TEXTURE_SHADOW_INPUT_LIGHTS 5    // shadow rays: the input lights S0 as integer texels
#define LGH_TEXTURE_SHADOW_QUEUE 7           // shadow rays, traced: the queue as texels
#define LGH_TEXTURE_FILTER_SIGNAL 4          // a-trous: the signal being filtered
#define LGH_TEXTURE_FILTER_SECOND 5          // a-trous: the sampled irradiance, or the raw ratio
#define LGH_TEXTURE_COMPOSITE_DIRECT 4
#define LGH_TEXTURE_COMPOSITE_INDIRECT 5
#define LGH_TEXTURE_COMPOSITE_VISIBILITY 6
#define LGH_TEXTURE_DISPLAY_IMAGE 0
#define LGH_TEXTURE_ACCUM_RAW_IRRADIANCE 4     // accumulation: this frame's unresolved irradiance
#define LGH_TEXTURE_ACCUM_IRRADIANCE_SUM 5     // accumulation history: sum of raw irradiance, a: frames
#define LGH_TEXTURE_ACCUM_RATIO_SUM 6          // accumulation history: shadowed and unshadowed luminance sums
#define LGH_TEXTURE_ACCUM_PREVIOUS_POSITION 7  // accumulation history: the surfaces it belongs to
#define LGH_TEXTURE_ACCUM_PREVIOUS_NORMAL 8
#define LGH_TEXTURE_ACCUM_HEAVIEST 9    // accumulation history: the frame with the largest mean weight
#define LGH_TEXTURE_ACCUM_RAW_RATIO 10  // accumulation under motion: this frame's raw ratio (a copy)
// The scene's BVH (render/scene/gpu_bvh.h), where every shader that traces reads it: the last three of the
// 16 units any compute shader has.
#define LGH_TEXTURE_BVH_NODE_FLOATS 13
#define LGH_TEXTURE_BVH_NODE_WORDS 14
#define LGH_TEXTURE_BVH_TRIANGLE_WORDS 15

// Image units, per pass.
#define LGH_IMAGE_TILED_POSITION 0             // interleave split
#define LGH_IMAGE_TILED_NORMAL 1               // interleave split
#define LGH_IMAGE_RESOLVED_IRRADIANCE 0        // interleave resolve
#define LGH_IMAGE_RESOLVED_FRAGMENT_COUNTS 1   // interleave resolve
#define LGH_IMAGE_FRAGMENT_COUNTS 0            // light pass (overdraw)
#define LGH_IMAGE_PYRAMID_FINER 0              // depth pyramid: the level read
#define LGH_IMAGE_PYRAMID_COARSER 1            // depth pyramid: the level written
#define LGH_IMAGE_DIRECT 0                     // direct light
#define LGH_IMAGE_BRUTE_FORCE_IRRADIANCE 0     // compute brute force
#define LGH_IMAGE_SHADOW_RATIO 0               // shadow rays
#define LGH_IMAGE_SHADOW_SAMPLED_IRRADIANCE 1  // shadow rays: the irradiance T is compared with
#define LGH_IMAGE_SHADOW_QUEUE 2               // shadow rays: the queued rays, written as texels
#define LGH_IMAGE_FILTER_OUT 0                 // a-trous
#define LGH_IMAGE_RTSLC_SHADOWED 0             // lightcuts: the shadowed irradiance estimate
#define LGH_IMAGE_RTSLC_UNSHADOWED 1           // lightcuts, ratio form: the same samples unshadowed
#define LGH_IMAGE_RTSLC_RATIO 2                // lightcuts, ratio form: the raw visibility ratio
#define LGH_IMAGE_RTSLC_SAMPLED 3              // lightcuts, ratio form: the unshadowed luminance
#define LGH_IMAGE_COMPOSITE_FINAL 0
#define LGH_IMAGE_COMPOSITE_INDIRECT 1
#define LGH_IMAGE_ACCUM_IRRADIANCE 0      // accumulation: in this frame's irradiance, out the accumulated
#define LGH_IMAGE_ACCUM_RATIO 1           // accumulation: in the raw ratio, out the accumulated one
#define LGH_IMAGE_ACCUM_IRRADIANCE_SUM 2  // accumulation: the new history
#define LGH_IMAGE_ACCUM_RATIO_SUM 3
#define LGH_IMAGE_ACCUM_POSITION 4
#define LGH_IMAGE_ACCUM_NORMAL 5
#define LGH_IMAGE_ACCUM_SAMPLED_IRRADIANCE 6  // accumulation: this frame's in, the accumulated out
#define LGH_IMAGE_ACCUM_HEAVIEST 7

// Uniform blocks.
#define LGH_UBO_FRAME 0
#define LGH_UBO_PASS 1

#endif
