#pragma once
// Invalid glTF files, one specification rule broken in each, for the strict-loading tests: the loader
// (gltf_strict_test.cpp, also run under AddressSanitizer + UBSan) and lgh-render (render_cli_test.cpp,
// exit status 1) must both reject each with a message that names the file and the problem.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace lgh::test {

struct MalformedGltf {
  std::string name;  // [A-Za-z0-9_]: also the test's name
  std::string rule;  // the Khronos glTF-Validator issue code (or the spec rule) it breaks
  std::function<std::filesystem::path(const std::filesystem::path& dir)> write;  // writes it into dir
  std::vector<std::string> expectedWords;                                        // the message must contain each
};

const std::vector<MalformedGltf>& malformedGltfCases();
// The valid scene every case starts from (a lit, textured quad and a camera), unedited.
std::filesystem::path writeUnbrokenGltf(const std::filesystem::path& dir);
// The same with an animation the animation cases break: the lamp (node 2) moves from (0, 2, 0) to
// (1, 2, 0) over the first second, linearly.
std::filesystem::path writeUnbrokenAnimatedGltf(const std::filesystem::path& dir);

}  // namespace lgh::test
