#pragma once

// Blending functions: how much of a light at distance d each level of the hierarchy contributes.
//
// Level l answers for distances around R_l = alpha h_l. Since h_{l+1} = 2 h_l, also R_{l+1} = 2 R_l,
// so the band where level l fades out, (R_l, 2R_l), is exactly the band where level l+1 fades in,
// (R_{l+1}/2, R_{l+1}), and on it the fade-out 2 - d/R_l and the fade-in 2d/R_{l+1} - 1 = d/R_l - 1
// add up to 1. The finest level used has no fade-in (it answers for everything near) and the top
// level no fade-out (it answers for everything far), so over firstLevel..L the weights form a
// partition of unity for every d >= 0: no light is lost or counted twice, whatever alpha is.
// Larger alpha moves every band outwards: each light is represented by finer levels for longer.
//
//   role     d <= R/2   R/2 < d <= R   R < d < 2R   d >= 2R
//   Finest   1          1              2 - d/R      0
//   Middle   0          2d/R - 1       2 - d/R      0
//   Top      0          2d/R - 1       1            1
//   Only     1          1              1            1        (a single level: brute force over it)

namespace lgh {

enum class LevelRole { Finest, Middle, Top, Only };

// The role of `level` when levels firstLevel..levels are blended.
inline LevelRole levelRole(int level, int firstLevel, int levels) {
  if (firstLevel == levels) return LevelRole::Only;
  if (level == firstLevel) return LevelRole::Finest;
  if (level == levels) return LevelRole::Top;
  return LevelRole::Middle;
}

// Weight of a light of a level with the given role at distance d, with R = R_level.
// Each branch divides by R only where R < d, so R = 0 never divides by zero.
inline double blendWeight(LevelRole role, double d, double R) {
  if (role == LevelRole::Only) return 1.0;
  const bool fadesIn = role == LevelRole::Middle || role == LevelRole::Top;
  const bool fadesOut = role == LevelRole::Finest || role == LevelRole::Middle;
  if (d <= 0.5 * R) return fadesIn ? 0.0 : 1.0;
  if (d <= R) return fadesIn ? 2.0 * d / R - 1.0 : 1.0;
  if (d < 2.0 * R) return fadesOut ? 2.0 - d / R : 1.0;
  return fadesOut ? 0.0 : 1.0;
}

}  // namespace lgh
