#include "render/passes/shadow_targets_pass.h"

#include <algorithm>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"
#include "shared/light_pass_types.h"

namespace lgh {
namespace {
constexpr unsigned kLocalSize = 256;
}  // namespace

ShadowTargetsPass::ShadowTargetsPass()
    : raceFromLights_(gl::Program::compute("shadow_targets.comp", {{"SHADOW_TARGETS_RACE", "1"}})),
      resolveFromLights_(gl::Program::compute("shadow_targets.comp")),
      raceFromGridLights_(gl::Program::compute(
          "shadow_targets.comp", {{"SHADOW_TARGETS_RACE", "1"}, {"SHADOW_TARGETS_FROM_GRID_LIGHTS", "1"}})),
      resolveFromGridLights_(gl::Program::compute("shadow_targets.comp", {{"SHADOW_TARGETS_FROM_GRID_LIGHTS", "1"}})) {
  maxBlockBytes_ = std::max(gl::maxStorageBlockBytes(), gl::kMinStorageBlockBytes);
}

void ShadowTargetsPass::release() {
  raceTimes_ = {};
  gridParams_ = {};
}

void ShadowTargetsPass::execute(const ShadowTargetsInputs& in, unsigned races, unsigned frameSeed, ShadowTargets& out) {
  const GpuHierarchy& hierarchy = in.hierarchy;
  out.races = races;
  const size_t entries = std::max<size_t>(hierarchy.gridLightCount * races, 1);
  const char* scaled = "the grid lights x shadow-targets";
  fitSize(out.targets, {passes::kShadowTargets, "targets", scaled}, entries * sizeof(GLuint));
  fitSize(raceTimes_, {passes::kShadowTargets, "race times", scaled}, entries * sizeof(GLuint));
  out.targets.clearUint(gpu::kNoLight);
  raceTimes_.clearUint(0xffffffffu);  // above every finite time's bits
  raceTimes_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS4);
  out.targets.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS5);
  // Finest level first: a gathered level hands on the draws of the level below.
  // (No grid lights, e.g. no input lights at all: nothing to draw; the lookups may not exist.)
  const int levels = hierarchy.gridLightCount > 0 ? int(hierarchy.lookups.size()) - 1 : 0;
  for (int level = 1; level <= levels; ++level) {
    const unsigned seed = frameSeed ^ (0x632be5abu * unsigned(level));
    runLevel(raceFromLights_, raceFromGridLights_, in, level, races, seed);
    runLevel(resolveFromLights_, resolveFromGridLights_, in, level, races, seed);
  }
  gl::checkErrors("shadow targets");
}

void ShadowTargetsPass::runLevel(const gl::Program& fromLights, const gl::Program& fromGridLights,
                                 const ShadowTargetsInputs& in, int level, unsigned races, unsigned seed) {
  const GpuHierarchy& hierarchy = in.hierarchy;
  const LghLevelLookup& lookup = hierarchy.lookups[size_t(level)];
  const gpu::LghGridParams params = gridParamsFor(hierarchy.grid, level, lookup.capacity);
  gl::ensureSize(gridParams_, {passes::kShadowTargets, "grid parameters"}, sizeof params);
  gridParams_.update(&params, sizeof params);
  gridParams_.bindBase(GL_UNIFORM_BUFFER, LGH_UBO_PASS);
  lookup.keys.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  lookup.slotIndex.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  auto dispatch = [&](const gl::Program& program, size_t count, size_t base, size_t index) {
    program.set("sourceCount", GLuint(count));
    program.set("sourceBase", GLuint(base));
    program.set("sourceIndex", GLuint(index));
    program.set("levelOffset", GLuint(hierarchy.levels[size_t(level)].offset));
    program.set("races", GLuint(races));
    program.set("seed", GLuint(seed));
    program.dispatch1D(count, kLocalSize);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  };
  if (level >= 2 && hierarchy.gathered) {
    const LghLevelRange& below = hierarchy.levels[size_t(level) - 1];
    hierarchy.gridLights.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
    dispatch(fromGridLights, below.count, below.offset, below.offset);
    return;
  }
  // S0 in chunks of one storage block.
  const size_t chunk = lightChunkSize(maxBlockBytes_);
  for (size_t first = 0; first < in.inputLightCount; first += chunk) {
    const size_t count = std::min(chunk, in.inputLightCount - first);
    in.inputLights.bindRange(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0, first * sizeof(gpu::GpuLight),
                             count * sizeof(gpu::GpuLight));
    dispatch(fromLights, count, 0, first);
  }
}

}  // namespace lgh
