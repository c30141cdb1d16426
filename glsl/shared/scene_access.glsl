// Surface properties at a ray hit for compute shaders: position, geometric normal, albedo and
// emission (shared/scene_materials.glsl: material factors x textures x vertex colour).
#ifndef LGH_SCENE_ACCESS_GLSL
#define LGH_SCENE_ACCESS_GLSL
#include "shared/bindings.h"
#include "shared/bvh_traverse.glsl"
#include "shared/scene_types.h"

struct HitSurface {
  vec3 position;
  vec3 normal;  // geometric, unit, facing the incoming ray
  vec3 albedo;
  vec3 emission;
};

HitSurface hitSurface(vec3 origin, vec3 direction, RayHit hit) {
  HitSurface s;
  s.position = origin + hit.t * direction;
  SurfacePoint p = surfacePoint(hit.sceneTriangle, hit.barycentrics);
  s.albedo = surfaceAlbedo(p);
  s.emission = surfaceEmission(p);
  BvhTriangle triangle = bvhTriangle(hit.bvhTriangle);
  vec3 n = cross(triangle.edge1, triangle.edge2);
  float len = length(n);
  s.normal = len > 0.0 ? n / len : -direction;
  if (dot(s.normal, direction) > 0.0) s.normal = -s.normal;
  return s;
}
#endif
