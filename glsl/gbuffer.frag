#version 450 core
#include "shared/bindings.h"
#include "shared/frame.glsl"
in vec3 worldPosition;
in vec3 worldNormal;
in vec2 texcoord;
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outEmission;

layout(binding = LGH_TEXTURE_MATERIAL_BASE_COLOR) uniform sampler2D baseColorTexture;  // white when the material has none
layout(binding = LGH_TEXTURE_MATERIAL_EMISSIVE) uniform sampler2D emissiveTexture;
uniform vec4 baseColorFactor;
uniform vec3 emissionFactor;

void main() {
  vec3 n = normalize(worldNormal);
  // Materials are treated as double-sided: shade the side the camera sees.
  vec3 toCamera = frame.cameraPosition.xyz - worldPosition;
  if (dot(n, toCamera) < 0.0) n = -n;
  if (any(isnan(n))) n = normalize(toCamera);
  outPosition = vec4(worldPosition, 1.0);
  outNormal = vec4(n, 0.0);
  outAlbedo = vec4(clamp(baseColorFactor.rgb * texture(baseColorTexture, texcoord).rgb, 0.0, 1.0), 1.0);
  outEmission = vec4(emissionFactor * texture(emissiveTexture, texcoord).rgb, 1.0);
}
