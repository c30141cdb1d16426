#pragma once
// The passes' names: FrameStats::passes times them under these (benchmarks and the viewer look them up),
// and the GPU memory registry (gl/memory.h) sums what each holds under the same names.

namespace lgh {

// In frame order.
namespace passes {
inline constexpr const char* kBvhBuild = "BVH build";  // over vertices an animation moved (SceneGpu::follow)
inline constexpr const char* kGBuffer = "G-buffer";
inline constexpr const char* kDirectLight = "direct light";
inline constexpr const char* kInputLights = "input lights";
inline constexpr const char* kLghBuild = "LGH build";
inline constexpr const char* kInterleaveSplit = "interleave split";
inline constexpr const char* kLightPass = "light pass";
inline constexpr const char* kInterleaveResolve = "interleave resolve";
inline constexpr const char* kShadowTargets = "shadow targets";
inline constexpr const char* kShadowRays = "shadow rays";
inline constexpr const char* kAccumulation = "accumulation";
inline constexpr const char* kShadowFilter = "shadow filter";
inline constexpr const char* kComposite = "composite";
// The stochastic lightcuts (--indirect-method rtslc) in place of the LGH's passes.
inline constexpr const char* kLightTreeBuild = "light tree build";
inline constexpr const char* kLightcutCuts = "lightcut cuts";
inline constexpr const char* kLightcutSampling = "lightcut sampling";
inline constexpr const char* kIrradianceFilter = "irradiance filter";
// Owners of GPU memory that are not passes.
inline constexpr const char* kScene = "scene";             // geometry, BVH, materials, textures, punctual lights
inline constexpr const char* kFrameSetup = "frame setup";  // the frame's uniforms
}  // namespace passes

// What the size of the frame's targets follows, for memory errors (gl::Label::scaledBy).
inline constexpr const char* kImageSize = "width x height";

}  // namespace lgh
