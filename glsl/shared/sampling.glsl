// Random numbers and the sampling routines of light paths.
#ifndef LGH_SAMPLING_GLSL
#define LGH_SAMPLING_GLSL

const float kPi = 3.14159265358979;

// PCG hash (Jarzynski & Olano 2020): a good 32-bit hash of a counter, so every path and pixel gets
// its own independent stream from (index, seed) without stored state.
uint pcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

struct Rng {
  uint state;
};
Rng makeRng(uint index, uint seed) { return Rng(pcgHash(index ^ pcgHash(seed + 0x9e3779b9u))); }
float nextFloat(inout Rng rng) {
  rng.state = pcgHash(rng.state);
  return float(rng.state >> 8u) * (1.0 / 16777216.0);  // [0, 1)
}

// Orthonormal basis around a unit normal (Duff et al. 2017), valid for every n.
void makeBasis(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

vec3 sampleUniformSphere(vec2 u) {
  float z = 1.0 - 2.0 * u.x, r = sqrt(max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), z);
}

// Direction within angle acos(cosMax) of `axis`, uniform in solid angle: pdf 1 / (2 pi (1 - cosMax)).
vec3 sampleUniformCone(vec2 u, vec3 axis, float cosMax) {
  float cosTheta = 1.0 - u.x * (1.0 - cosMax), sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * kPi * u.y;
  vec3 t, b;
  makeBasis(axis, t, b);
  return sinTheta * cos(phi) * t + sinTheta * sin(phi) * b + cosTheta * axis;
}

// Cosine-weighted direction around n: pdf cos(theta) / pi.
vec3 sampleCosineHemisphere(vec2 u, vec3 n) {
  float r = sqrt(u.x), phi = 2.0 * kPi * u.y;
  vec3 t, b;
  makeBasis(n, t, b);
  return r * cos(phi) * t + r * sin(phi) * b + sqrt(max(0.0, 1.0 - u.x)) * n;
}

// Uniform point on a triangle as barycentrics of (v1, v2).
vec2 sampleTriangle(vec2 u) {
  float su = sqrt(u.x);
  return vec2(su * (1.0 - u.y), su * u.y);
}

// Uniform point on the unit disk (concentric mapping keeps strata compact).
vec2 sampleDisk(vec2 u) {
  vec2 o = 2.0 * u - 1.0;
  if (o == vec2(0.0)) return vec2(0.0);
  float r, theta;
  if (abs(o.x) > abs(o.y)) {
    r = o.x;
    theta = (kPi / 4.0) * (o.y / o.x);
  } else {
    r = o.y;
    theta = kPi / 2.0 - (kPi / 4.0) * (o.x / o.y);
  }
  return r * vec2(cos(theta), sin(theta));
}
#endif
