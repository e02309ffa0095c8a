#include "render/frames.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace fissure {

namespace fs = std::filesystem;

namespace {

std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = name + "=\"";
  const auto start = tag.find(key);
  if (start == std::string::npos) return "";
  const auto begin = start + key.size();
  return tag.substr(begin, tag.find('"', begin) - begin);
}

}  // namespace

std::vector<FrameFiles> list_frames(const std::string& out_dir) {
  if (!fs::is_directory(out_dir))
    throw InputError(out_dir, "", "no such output folder (run `fissure run` first)");
  const fs::path index = fs::path(out_dir) / "particles.pvd";
  std::ifstream in(index);
  if (!in) throw InputError(out_dir, "", "no particles.pvd here: not the output folder of a run");
  std::stringstream text;
  text << in.rdbuf();
  const std::string pvd = text.str();
  std::vector<FrameFiles> frames;
  for (auto pos = pvd.find("<DataSet"); pos != std::string::npos;
       pos = pvd.find("<DataSet", pos + 1)) {
    const std::string tag = pvd.substr(pos, pvd.find('>', pos) - pos);
    const std::string file = attribute(tag, "file");
    if (file.empty()) continue;
    FrameFiles frame;
    frame.time = std::stod(attribute(tag, "timestep").empty() ? "0" : attribute(tag, "timestep"));
    frame.stem = fs::path(file).stem().string();
    frame.particles = (fs::path(out_dir) / file).string();
    if (!fs::exists(frame.particles))
      throw InputError(index.string(), "", "lists " + file + ", which is missing");
    std::string number = frame.stem.substr(frame.stem.find('_') + 1);
    for (const char* ext : {".obj", ".vtu"}) {
      const fs::path surface = fs::path(out_dir) / ("surface_" + number + ext);
      if (frame.surface.empty() && fs::exists(surface)) frame.surface = surface.string();
    }
    frames.push_back(frame);
  }
  if (frames.empty()) throw InputError(index.string(), "", "lists no frame");
  return frames;
}

}  // namespace fissure
