#pragma once
// The scenes shipped with amphora, for `amphora run` without a scene: each scene file's name
// and the first sentence of its leading comment.
#include <string>
#include <vector>

namespace amphora::io {

struct SceneEntry {
  std::string path;     ///< the file, as found
  std::string summary;  ///< first sentence of the file's leading comment block
};

/// The folder of shipped scenes: `scenes/` under the working directory if there is one, else
/// the source tree's (compiled in).
std::string shipped_scene_dir();

/// Every *.toml in `dir`, sorted by name.
std::vector<SceneEntry> list_scenes(const std::string& dir);

}  // namespace amphora::io
