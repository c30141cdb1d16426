#version 450 core
#include "shared/bindings.h"
#include "shared/frame.glsl"
#include "shared/material_eval.h"
in vec3 worldPosition;
in vec3 worldNormal;
in vec4 texcoords;
in vec4 vertexColor;
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outEmission;

layout(binding = LGH_TEXTURE_MATERIAL_BASE_COLOR) uniform sampler2D baseColorTexture;  // white when the material has none
layout(binding = LGH_TEXTURE_MATERIAL_EMISSIVE) uniform sampler2D emissiveTexture;
// The material as plain uniforms, not read from the materials SSBO: on llvmpipe helper invocations
// (the 2x2-quad neighbours that implicit derivatives need) read SSBOs as zero, which broke the uv
// derivatives along every triangle edge (a mip-level seam, measured 2026-12-01). Uniforms are safe.
uniform vec4 baseColorFactor;
uniform vec3 emission;
uniform float alphaCutoff;
uniform uint baseColorTexCoord, emissiveTexCoord;
uniform vec4 baseColorUvRow0, baseColorUvRow1, emissiveUvRow0, emissiveUvRow1;

void main() {
  GpuMaterial m;
  m.baseColorFactor = baseColorFactor;
  m.emission = emission;
  m.alphaCutoff = alphaCutoff;
  m.baseColorTexCoord = baseColorTexCoord;
  m.emissiveTexCoord = emissiveTexCoord;
  m.baseColorUvRow0 = baseColorUvRow0;
  m.baseColorUvRow1 = baseColorUvRow1;
  m.emissiveUvRow0 = emissiveUvRow0;
  m.emissiveUvRow1 = emissiveUvRow1;
  vec4 base = texture(baseColorTexture, baseColorUv(m, texcoords));
  if (alphaCutOut(m, base.a, vertexColor.a)) discard;  // alphaMode MASK
  vec3 n = normalize(worldNormal);
  // Single-sided materials reach here only with front faces (the pass culls back faces); double-sided
  // ones shade the side the camera sees, as glTF asks (the back face's normal reversed).
  vec3 toCamera = frame.cameraPosition.xyz - worldPosition;
  if (dot(n, toCamera) < 0.0) n = -n;
  if (any(isnan(n))) n = normalize(toCamera);
  outPosition = vec4(worldPosition, 1.0);
  outNormal = vec4(n, 0.0);
  outAlbedo = vec4(clamp(m.baseColorFactor.rgb * base.rgb * vertexColor.rgb, 0.0, 1.0), 1.0);
  outEmission = vec4(m.emission * texture(emissiveTexture, emissiveUv(m, texcoords)).rgb, 1.0);
}
