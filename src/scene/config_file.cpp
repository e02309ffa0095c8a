#include "scene/config_file.hpp"

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/error.hpp"

namespace fissure {

namespace {

constexpr int kMaxBaseDepth = 8;

// `over`'s keys replace `base`'s; where both hold a map under a key, the maps merge.
YAML::Node merge(const YAML::Node& base, const YAML::Node& over) {
  YAML::Node result = YAML::Clone(base);
  for (const auto& entry : over) {
    const std::string key = entry.first.as<std::string>();
    const YAML::Node mine = result[key];
    if (mine.IsDefined() && mine.IsMap() && entry.second.IsMap())
      result[key] = merge(mine, entry.second);
    else
      result[key] = YAML::Clone(entry.second);
  }
  return result;
}

YAML::Node load(const std::string& path, std::vector<std::string>& chain) {
  std::ifstream in(path);
  if (!in) {
    if (chain.empty()) throw InputError(path, "", "cannot open the config file");
    throw InputError(chain.back(), "base", fmt::format("cannot open the base file '{}'", path));
  }
  std::stringstream text;
  text << in.rdbuf();
  YAML::Node root = parse_yaml(text.str(), path);
  const YAML::Node base = root["base"];
  if (!base) return root;
  if (!base.IsScalar()) throw InputError(path, "base", "expected the path of a scene file");
  const auto canonical = std::filesystem::weakly_canonical(path).string();
  for (const auto& seen : chain)
    if (seen == canonical) throw InputError(path, "base", "the base files include each other");
  if (static_cast<int>(chain.size()) >= kMaxBaseDepth)
    throw InputError(path, "base", fmt::format("more than {} nested base files", kMaxBaseDepth));
  chain.push_back(canonical);
  const auto base_path =
      (std::filesystem::path(path).parent_path() / base.as<std::string>()).lexically_normal();
  const YAML::Node parent = load(base_path.string(), chain);
  chain.pop_back();
  root.remove("base");
  return merge(parent, root);
}

}  // namespace

YAML::Node parse_yaml(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp's own message for this is "bad file".
    throw InputError(file, "",
                     fmt::format("not valid YAML (line {}, column {}): nested more than {} levels "
                                 "deep",
                                 e.mark.line + 1, e.mark.column + 1, e.depth() - 1));
  } catch (const YAML::Exception& e) {
    throw InputError(file, "",
                     fmt::format("not valid YAML (line {}, column {}): {}", e.mark.line + 1,
                                 e.mark.column + 1, e.msg));
  }
  if (!root.IsMap()) throw InputError(file, "", "expected a YAML map at the top level");
  return root;
}

YAML::Node load_yaml_with_base(const std::string& path) {
  std::vector<std::string> chain;
  return load(path, chain);
}

}  // namespace fissure
