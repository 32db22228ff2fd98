#include "io/scene_catalog.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace amphora::io {
namespace {

std::string shorten(std::string text) {
  constexpr size_t width = 96;
  if (text.size() > width) text = text.substr(0, text.rfind(' ', width - 4)) + " ...";
  return text;
}

/// The leading `#` lines of a scene file joined, cut after the first sentence.
std::string first_sentence(const std::string& path) {
  std::ifstream in(path);
  std::string line, text;
  while (std::getline(in, line) && line.rfind('#', 0) == 0) {
    const auto start = line.find_first_not_of("# ");
    if (start == std::string::npos) break;
    text += (text.empty() ? "" : " ") + line.substr(start);
    for (size_t stop = 0; stop < text.size(); ++stop)
      if ((text[stop] == '.' || text[stop] == ':') &&
          (stop + 1 == text.size() || text[stop + 1] == ' ')) {
        text.resize(stop);
        return shorten(text);
      }
  }
  return shorten(text);
}

}  // namespace

std::string shipped_scene_dir() {
  if (std::filesystem::is_directory("scenes")) return "scenes";
  return AMPHORA_SOURCE_SCENES;
}

std::vector<SceneEntry> list_scenes(const std::string& dir) {
  std::vector<SceneEntry> out;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().extension() == ".toml")
      out.push_back({entry.path().string(), first_sentence(entry.path().string())});
  std::sort(out.begin(), out.end(),
            [](const SceneEntry& a, const SceneEntry& b) { return a.path < b.path; });
  return out;
}

}  // namespace amphora::io
