#version 450 core
// Light paths from the scene's emitters through the BVH, depositing an oriented VPL at every diffuse
// hit (LGH_VPL_PATHS), or points on emissive triangles as direct lights (LGH_EMITTER_SAMPLES).
//
// Every record has a fixed slot, so S0 comes out in the same order on every run whatever the order the
// threads run in: emitter sample i writes slot i; path p writes its VPL of bounce b to slot
// p * maxBounces + b, and a path that ends early leaves its remaining slots empty (flags = 0), removed
// afterwards by a stable compaction (vpl_compact.comp).
//
// A path starts with flux Phi_e / (p_e P) (emitter power over its selection probability and the path
// count), so the VPLs' total flux is exact in expectation. At a hit with albedo rho the surface
// reflects flux * rho as a cosine lobe: a VPL of peak intensity flux * rho / pi. The path continues in
// a cosine-distributed direction, where the Lambertian BRDF times cosine over the pdf is exactly rho.
layout(local_size_x = 64) in;
#include "shared/color.glsl"
#include "shared/dispatch.glsl"
#include "shared/lgh_types.h"
#include "shared/octahedral.h"
#include "shared/ray_offset.h"
#include "shared/sampling.glsl"
#include "shared/scene_access.glsl"

layout(std430, binding = LGH_BINDING_PUNCTUAL_LIGHTS) readonly buffer PunctualLights { GpuPunctualLight lights[]; };
layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Emitters { GpuEmitter emitters[]; };
layout(std430, binding = LGH_BINDING_PASS1) writeonly buffer Output { GpuLight outputLights[]; };

uniform uint sampleCount;      // paths, or emitter samples, in all batches
uniform uint firstSample;      // this batch's first (a batch's records fit one storage block)
uniform uint batchCount;       // and its count
uniform uint maxBounces;
uniform uint seed;
uniform uint outputOffset;     // first element of outputLights this pass writes
uniform vec4 sceneSphere;      // xyz centre, w radius: where directional light enters

uint chooseEmitter(float u) {  // binary search of the inclusive CDF
  uint lo = 0u, hi = uint(emitters.length()) - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (emitters[mid].cdf > u) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

void emit(uint slot, vec3 position, vec3 normal, vec3 intensity) {
  outputLights[outputOffset + slot] = GpuLight(position, octEncode(normal), intensity, kLightOriented);
}

// A point on an emissive triangle, its front-face normal and its radiance there (emissive texture included).
void sampleEmissiveTriangle(GpuEmitter e, inout Rng rng, out vec3 position, out vec3 normal, out vec3 radiance) {
  vec2 b = sampleTriangle(vec2(nextFloat(rng), nextFloat(rng)));
  position = e.v0 + b.x * e.edge1 + b.y * e.edge2;
  normal = normalize(cross(e.edge1, e.edge2));
  SurfacePoint p = surfacePoint(e.light, b);
  radiance = e.radiance * fetchTexture(p.material.emissiveTexture, emissiveUv(p.material, p.texcoords)).rgb;
  // A point that alphaMode MASK cuts out emits nothing (the sample still counts: unbiased).
  if (surfaceCutOut(e.light, b)) radiance = vec3(0.0);
}

void main() {
  uint local = lghGlobalIndex();
  if (local >= batchCount || emitters.length() == 0) return;
  uint index = firstSample + local;  // the sample's random sequence is its own, whatever the batches
  Rng rng = makeRng(index, seed);
  GpuEmitter e = emitters[chooseEmitter(nextFloat(rng))];
  float scale = 1.0 / (e.selectionPdf * float(sampleCount));

#ifdef LGH_EMITTER_SAMPLES
  // A patch of area A / (p M) on average: peak intensity L A / (p M) (flux pi L A / (p M), over pi).
  vec3 position, normal, radiance;
  sampleEmissiveTriangle(e, rng, position, normal, radiance);
  float area = 0.5 * length(cross(e.edge1, e.edge2));
  emit(local, position, normal, radiance * area * scale);
#else
  vec3 origin, direction, flux;
  if (e.kind == kEmitterTriangle) {
    vec3 normal, radiance;
    sampleEmissiveTriangle(e, rng, origin, normal, radiance);
    direction = sampleCosineHemisphere(vec2(nextFloat(rng), nextFloat(rng)), normal);
    flux = kPi * radiance * 0.5 * length(cross(e.edge1, e.edge2)) * scale;
    origin = offsetRayOrigin(origin, normal);
  } else {
    GpuPunctualLight l = lights[e.light];
    vec2 u = vec2(nextFloat(rng), nextFloat(rng));
    if (l.type == kLightDirectional) {
      // Parallel rays from a disk that covers the scene's bounding sphere, upstream of it.
      vec3 t, b;
      makeBasis(l.direction, t, b);
      vec2 d = sceneSphere.w * sampleDisk(u);
      origin = sceneSphere.xyz - sceneSphere.w * l.direction + d.x * t + d.y * b;
      direction = l.direction;
      flux = l.intensity * kPi * sceneSphere.w * sceneSphere.w * scale;
    } else if (l.type == kLightSpot) {
      // Uniform in the outer cone, weighted by glTF's falloff (unbiased for any cone angles).
      origin = l.position;
      direction = sampleUniformCone(u, l.direction, l.outerConeCos);
      float t = clamp((dot(direction, l.direction) - l.outerConeCos) / max(l.innerConeCos - l.outerConeCos, 1e-4), 0.0, 1.0);
      flux = l.intensity * (t * t) * 2.0 * kPi * (1.0 - l.outerConeCos) * scale;
    } else {
      origin = l.position;
      direction = sampleUniformSphere(u);
      flux = l.intensity * 4.0 * kPi * scale;
    }
  }

  for (uint bounce = 0u; bounce < maxBounces; ++bounce) {
    RayHit hit;
    if (!traceClosestHit(origin, direction, 0.0, uintBitsToFloat(0x7f800000u), hit)) break;
    HitSurface s = hitSurface(origin, direction, hit);
    flux *= s.albedo;  // the flux the surface reflects
    if (!(luminance(flux) > 0.0)) break;
    emit(local * maxBounces + bounce, s.position, s.normal, flux * (1.0 / kPi));
    origin = offsetRayOrigin(s.position, s.normal);
    direction = sampleCosineHemisphere(vec2(nextFloat(rng), nextFloat(rng)), s.normal);
  }
#endif
}
