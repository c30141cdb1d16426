// Lets one header declare a GPU struct for both C++ and GLSL (std430 / std140).
// In C++ the GLSL vector types map to glm, structs get 16-byte alignment, and
// GPU_CHECK_SIZE / GPU_CHECK_OFFSET pin the layout with static_assert. In GLSL the macros vanish.
//
// Layout rules used by every shared struct (so std430 and C++ agree without hand padding):
//   a vec3 is always followed by one 4-byte scalar; vec4/uvec4/mat4 anywhere; scalars in groups of four;
//   struct sizes are multiples of 16.
#ifndef LGH_GPU_PRELUDE_H
#define LGH_GPU_PRELUDE_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>
namespace lgh::gpu {
using uint = std::uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec2 = glm::uvec2;
using uvec3 = glm::uvec3;
using uvec4 = glm::uvec4;
using ivec2 = glm::ivec2;
using ivec3 = glm::ivec3;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
// So that functions written once in a shared header read the same as GLSL.
using glm::abs;
using glm::clamp;
using glm::cross;
using glm::dot;
using glm::exp2;
using glm::floatBitsToInt;
using glm::floatBitsToUint;
using glm::floor;
using glm::intBitsToFloat;
using glm::max;
using glm::min;
using glm::pow;
using glm::sqrt;
using glm::uintBitsToFloat;
}  // namespace lgh::gpu
#define GPU_NAMESPACE_BEGIN namespace lgh::gpu {
#define GPU_NAMESPACE_END }
#define GPU_STRUCT(name) struct alignas(16) name
#define GPU_CONST inline constexpr
#define GPU_FUNC inline
#define GPU_OUT(type) type&
#define GPU_CHECK_SIZE(type, bytes) static_assert(sizeof(type) == (bytes), #type " must match its GLSL std430 size")
#define GPU_CHECK_OFFSET(type, member, bytes) \
  static_assert(offsetof(type, member) == (bytes), #type "::" #member " must match its GLSL std430 offset")
#else
#define GPU_NAMESPACE_BEGIN
#define GPU_NAMESPACE_END
#define GPU_STRUCT(name) struct name
#define GPU_CONST const
#define GPU_FUNC
#define GPU_OUT(type) out type
#define GPU_CHECK_SIZE(type, bytes)
#define GPU_CHECK_OFFSET(type, member, bytes)
#endif

#endif  // LGH_GPU_PRELUDE_H
