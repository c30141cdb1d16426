#version 450 core
// Real-time stochastic lightcuts (Lin & Yuksel 2020; docs/design.md §12), the peer method of the LGH over
// the same input lights S0, the same rays and the same light shading:
//   cuts      one invocation per B x B block: a cut of at most n nodes of the light tree, chosen at a random
//             pixel of the block by greedy splitting of the node with the largest error bound (§3.2-3.3;
//             B = 1: every pixel its own cut)
//   sampling  one invocation per pixel: for each of its cut nodes one descent to a leaf by Eq. 1-2's child
//             probabilities at this pixel, the leaf's light shaded as the LGH shades S0 (lgh_shading.glsl,
//             same clamp) and one shadow ray to it (same origin offset and ray end as shadow_rays.comp),
//             f / p summed; with m x m interleaving (§3.4, Eq. 3) the cut has n m^2 nodes and each pixel
//             of an m x m group takes n of them, rotated every frame, times m^2
// The cut partitions the lights (a stratification), so the sum is an unbiased estimate of the exact
// shadowed irradiance (Yuksel 2020, §5), a dead branch counting as a zero sample (with interleaving, every
// m^2 frames are).
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/bindings.h"
#include "shared/bvh_traverse.glsl"
#include "shared/color.glsl"
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"
#include "shared/lgh_shading.glsl"
#include "shared/lgh_types.h"
#include "shared/light_tree_types.h"
#include "shared/light_levels.h"
#include "shared/octahedral.h"
#include "shared/ray_offset.h"
#include "shared/sampling.glsl"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Lights { GpuLight inputLights[]; };
layout(std430, binding = LGH_BINDING_PASS1) readonly buffer Nodes { GpuLightTreeNode nodes[]; };
layout(std430, binding = LGH_BINDING_PASS2) readonly buffer Bounds { LghBoundsResult bounds; };
layout(std430, binding = LGH_BINDING_PASS3) buffer Cuts { uint cuts[]; };  // kMaxCutNodes per block, kNoCutNode: unused
layout(rgba32f, binding = LGH_IMAGE_RTSLC_SHADOWED) uniform writeonly image2D shadowedOut;
// The ratio form's (rtslc.ratioOutputs): the same samples unshadowed, and the visibility ratio as the shadow
// filter reads the LGH's (shadowed / unshadowed luminance, 0, unshadowed luminance, 1 frame) with the
// unshadowed luminance apart as the irradiance its samples were drawn against.
layout(rgba32f, binding = LGH_IMAGE_RTSLC_UNSHADOWED) uniform writeonly image2D unshadowedOut;
layout(rgba32f, binding = LGH_IMAGE_RTSLC_RATIO) uniform writeonly image2D ratioOut;
layout(r32f, binding = LGH_IMAGE_RTSLC_SAMPLED) uniform writeonly image2D sampledOut;
#include "shared/light_tree.glsl"

layout(std140, binding = LGH_UBO_PASS) uniform Rtslc { RtslcUniforms rtslc; };

// The block's representative: a random pixel of it, or where that shows no surface its first that does.
bool representative(uvec2 block, ivec2 size, inout Rng rng, out Surface s) {
  ivec2 corner = ivec2(block * rtslc.blockSize);
  ivec2 extent = min(ivec2(rtslc.blockSize), size - corner);
  int pick = min(int(nextFloat(rng) * float(extent.x * extent.y)), extent.x * extent.y - 1);
  s = loadSurface(corner + ivec2(pick % extent.x, pick / extent.x));
  for (int i = 0; !s.valid && i < extent.x * extent.y; ++i) s = loadSurface(corner + ivec2(i % extent.x, i / extent.x));
  return s.valid;
}

void selectCut(uvec2 block, ivec2 size) {
  uint base = (block.y * rtslc.blocksPerRow + block.x) * kMaxCutNodes;
  Rng rng = makeRng(block.y * rtslc.blocksPerRow + block.x, rtslc.frameSeed ^ 0x2c1b3c6du);
  Surface s;
  uint cut[kMaxCutNodes];
  float errors[kMaxCutNodes];
  uint count = 1u;
  cut[0] = 1u;
  // The root is split first whatever its bound (the authors' 1e27); a leaf never is.
  errors[0] = rtslc.leafCount > 1u ? uintBitsToFloat(0x7f800000u) : 0.0;
  if (representative(block, size, rng, s)) {
    // The cut's distance floor: the authors' share of the lights' box, and at least the shading's clamp.
    float minDistance = rtslc.errorLimit * distance(vec3(fromOrderedBits(bounds.allLower[0]), fromOrderedBits(bounds.allLower[1]),
                                                         fromOrderedBits(bounds.allLower[2])),
                                                    vec3(fromOrderedBits(bounds.allUpper[0]), fromOrderedBits(bounds.allUpper[1]),
                                                         fromOrderedBits(bounds.allUpper[2])));
    minDistance = max(minDistance, rtslc.clampDistance);
    while (count < rtslc.cutSize) {
      uint worst = 0u;
      for (uint i = 1u; i < count; ++i)
        if (errors[i] > errors[worst]) worst = i;
      if (!(errors[worst] > 0.0)) break;  // every node a leaf, or unable to light the representative
      uint node = cut[worst];
      cut[worst] = 2u * node;
      errors[worst] = cutErrorBound(2u * node, rtslc.leafCount, s.position, s.normal, minDistance);
      if (nodes[2u * node + 1u].intensity > 0.0) {  // a second child of padding only is not kept
        cut[count] = 2u * node + 1u;
        errors[count++] = cutErrorBound(2u * node + 1u, rtslc.leafCount, s.position, s.normal, minDistance);
      }
    }
  }
  for (uint i = 0u; i < kMaxCutNodes; ++i) cuts[base + i] = i < count ? cut[i] : kNoCutNode;
}

void sampleLights(ivec2 pixel) {
  Surface s = loadSurface(pixel);
  vec3 shadowed = vec3(0.0), unshadowed = vec3(0.0);
  if (s.valid && rtslc.leafCount > 0u) {
    uvec2 block = uvec2(pixel) / rtslc.blockSize;
    uint base = (block.y * rtslc.blocksPerRow + block.x) * kMaxCutNodes;
    uint cutSize = 0u;
    while (cutSize < kMaxCutNodes && cuts[base + cutSize] != kNoCutNode) ++cutSize;
    // Eq. 3: the pixel's place in its m x m group, rotated every frame, takes nodes [p c / m^2, (p + 1) c / m^2).
    uint m = rtslc.interleave, groupSize = m * m;
    uint place = (frame.resolution.z + m * (uint(pixel.y) % m) + uint(pixel.x) % m) % groupSize;
    uint first = place * cutSize / groupSize, last = (place + 1u) * cutSize / groupSize;
    vec3 origin = offsetRayOrigin(s.position, s.normal);
    Rng rng = makeRng(uint(pixel.y) * uint(frame.resolution.x) + uint(pixel.x), rtslc.frameSeed ^ 0x68e31da4u);
    for (uint i = first; i < last; ++i) {
      float probability;
      uint leaf = descendToLeaf(cuts[base + i], rtslc.leafCount, s.position, s.normal, rtslc.clampDistance, rng,
                                probability);
      // A dead branch: a zero sample. (A path's probability below the smallest normal float is drawn about
      // that rarely, and 1 / p of a denormal is infinite on llvmpipe, which flushes it.)
      if (leaf == 0u || !(probability >= 1.17549435e-38)) continue;
      uint light = nodes[leaf].lightIndex;
      if (light == kTreeNoLight) continue;  // padding: a cut of dark lights only
      ShadedLight l = decodeInputLight(inputLights[light]);
      vec3 f = lightContribution(l.position, l.intensity, l.meanNormal, l.omniFraction, s.position, s.normal,
                                 rtslc.clampDistance) /
               probability;
      if (f == vec3(0.0)) continue;
      unshadowed += f;
      // Stop short of the light by a relative margin, as shadow_rays.comp: VPLs sit on surfaces.
      vec3 toLight = l.position - origin;
      float rayLength = length(toLight);
      bool blocked = rayLength > 0.0 && traceAnyHit(origin, toLight / rayLength, 0.0, rayLength * (1.0 - 1e-3));
      if (!blocked) shadowed += f;
    }
    shadowed *= float(groupSize);
    unshadowed *= float(groupSize);
  }
  imageStore(shadowedOut, pixel, vec4(shadowed, 1.0));
  if (rtslc.ratioOutputs != 0u) {
    float u = luminance(unshadowed), ratio = u > 0.0 ? clamp(luminance(shadowed) / u, 0.0, 1.0) : 1.0;
    imageStore(unshadowedOut, pixel, vec4(unshadowed, 1.0));
    imageStore(ratioOut, pixel, vec4(ratio, 0.0, u, 1.0));
    imageStore(sampledOut, pixel, vec4(u));
  }
}

void main() {
  ivec2 size = ivec2(frame.resolution.xy);
  if (rtslc.stage == kRtslcCuts) {
    uvec2 block = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(block * rtslc.blockSize, uvec2(size)))) return;
    selectCut(block, size);
  } else {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, size))) return;
    sampleLights(pixel);
  }
}
