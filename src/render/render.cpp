#include "render/render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/external_program.hpp"
#include "io/vtu_reader.hpp"
#include "mesh/surface_formats.hpp"
#include "render/field_colors.hpp"
#include "render/frames.hpp"
#include "render/pov_writer.hpp"

namespace fissure {

namespace fs = std::filesystem;

namespace {

void require_program(const std::string& program, const std::string& package) {
  if (find_program(program).empty())
    throw RunError(
        fmt::format("`{}` not found on PATH: install the Debian package '{}' "
                    "(apt-get install {}, or scripts/setup)",
                    program, package, package));
}

// Every `every`-th frame, and always the last.
std::vector<FrameFiles> select_frames(const std::vector<FrameFiles>& all, int every) {
  std::vector<FrameFiles> chosen;
  for (std::size_t i = 0; i < all.size(); i += every) chosen.push_back(all[i]);
  if ((all.size() - 1) % every != 0) chosen.push_back(all.back());
  return chosen;
}

// The largest magnitude below which 99% of the values lie.
double upper_percentile(std::vector<double> values) {
  if (values.empty()) return 0;
  for (double& v : values) v = std::abs(v);
  const std::size_t k = values.size() - 1 - values.size() / 100;
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

void read_surface(const std::string& path, PovScene& scene) {
  if (fs::path(path).extension() == ".obj") {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    const SurfaceMesh mesh = mesh_detail::parse_obj(text.str(), path);
    scene.surface_vertices = mesh.vertices;
    scene.surface_triangles.assign(mesh.triangles.begin(), mesh.triangles.end());
    return;
  }
  const VtuGrid grid = read_vtu(path);
  scene.surface_vertices = grid.points;
  scene.surface_triangles.clear();
  long begin = 0;
  for (const long end : grid.offsets) {  // polygons as fans
    for (long k = begin + 1; k + 1 < end; ++k)
      scene.surface_triangles.insert(
          scene.surface_triangles.end(),
          {grid.connectivity[begin], grid.connectivity[k], grid.connectivity[k + 1]});
    begin = end;
  }
}

// The particles that still hold a bond (damage below 1): the dust of particles that lost every
// bond would otherwise stretch the camera's bounds. All of them when none qualifies.
std::vector<double> attached_points(const VtuGrid& grid) {
  const auto damage = grid.point_data.find("damage");
  if (damage == grid.point_data.end()) return grid.points;
  std::vector<double> points;
  for (long i = 0; i < grid.point_count(); ++i)
    if (damage->second.values[i] < 1.0)
      points.insert(points.end(), grid.points.begin() + 3 * i, grid.points.begin() + 3 * i + 3);
  return points.empty() ? grid.points : points;
}

}  // namespace

RenderSummary render_run(const std::string& out_dir, const RenderSettings& s,
                         const std::string& pictures_dir, bool progress) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<FrameFiles> frames = select_frames(list_frames(out_dir), s.every);
  require_program("povray", "povray");
  if (s.animation == "gif") require_program("convert", "imagemagick");
  if (s.animation == "mp4") require_program("ffmpeg", "ffmpeg");

  // First pass: the bounds over all frames, the colour range, the particle size.
  Bounds bounds;
  double top = 0;
  double radius = s.particle_radius;
  for (const FrameFiles& frame : frames) {
    const VtuGrid grid = read_vtu(frame.particles);
    bounds.include(robust_bounds(attached_points(grid)));
    top = std::max(top, upper_percentile(field_values(grid, s.field)));
    if (radius == 0 && grid.point_count() > 0) {
      const Bounds b = robust_bounds(grid.points);
      double volume = 1;
      for (int k = 0; k < 3; ++k) volume *= std::max(b.hi[k] - b.lo[k], 1e-12);
      radius = 0.6 * std::cbrt(volume / grid.point_count());
    }
  }
  if (bounds.empty()) throw InputError(out_dir, "", "the frames hold no particle");
  double lo = field_signed(s.field) ? -top : 0, hi = top;
  if (s.field == "damage") lo = 0, hi = 1;
  if (s.range_given) lo = s.range_min, hi = s.range_max;
  if (hi <= lo) hi = lo + 1;

  PovScene scene;
  scene.width = s.width;
  scene.height = s.height;
  const double aspect = static_cast<double>(s.width) / s.height;
  scene.camera = frame_bounds(bounds, s.view_angle, aspect);
  if (s.camera_given) scene.camera.position = s.camera_position, scene.camera.look_at = s.look_at;
  scene.floor_z = bounds.lo[2] - radius;
  scene.scene_size = 0;
  for (int k = 0; k < 3; ++k)
    scene.scene_size = std::max(scene.scene_size, bounds.hi[k] - bounds.lo[k]);
  scene.radius = radius;

  const fs::path folder =
      pictures_dir.empty() ? fs::path(out_dir) / "render" : fs::path(pictures_dir);
  fs::create_directories(folder);
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().extension() == ".png" || entry.path().extension() == ".pov")
      fs::remove(entry.path());
  const std::string log = (folder / "render.log").string();
  fs::remove(log);
  std::vector<std::string> pictures;
  std::vector<std::string> threads;
  if (const char* omp = std::getenv("OMP_NUM_THREADS"); omp && std::atoi(omp) > 0)
    threads.push_back(fmt::format("+WT{}", std::atoi(omp)));
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const FrameFiles& frame = frames[f];
    const VtuGrid grid = read_vtu(frame.particles);
    scene.points = &grid.points;
    scene.color_t = field_values(grid, s.field);
    for (double& t : scene.color_t) t = (t - lo) / (hi - lo);
    scene.surface_triangles.clear();
    if (s.show != "particles" && !frame.surface.empty()) read_surface(frame.surface, scene);
    if (s.show == "surface" && scene.surface_triangles.empty())
      throw InputError(
          out_dir, "render.show",
          fmt::format("surface asked for, but frame {} has no surface file", frame.stem));
    const std::string name = "frame" + frame.stem.substr(frame.stem.find('_'));
    write_pov((folder / (name + ".pov")).string(), scene);
    std::vector<std::string> argv = {"povray",
                                     "+I" + name + ".pov",
                                     "+O" + name + ".png",
                                     fmt::format("+W{}", s.width),
                                     fmt::format("+H{}", s.height),
                                     "+FN",
                                     "+A0.3",
                                     "-D",
                                     "-V"};
    argv.insert(argv.end(), threads.begin(), threads.end());
    const int status = run_program(argv, folder.string(), log);
    if (status != 0 || !fs::exists(folder / (name + ".png")))
      throw RunError(fmt::format("povray failed on {} (exit status {}); see {}",
                                 (folder / (name + ".pov")).string(), status, log));
    fs::remove(folder / (name + ".pov"));
    pictures.push_back(name + ".png");
    if (progress) fmt::print(stderr, "\rrender: frame {} / {}", f + 1, frames.size());
  }
  if (progress) fmt::print(stderr, "\n");

  RenderSummary summary;
  summary.frames = static_cast<int>(pictures.size());
  summary.folder = folder.string();
  if (s.animation == "gif") {
    std::vector<std::string> argv = {"convert", "-delay",
                                     fmt::format("{}", std::max(1L, std::lround(100 / s.fps))),
                                     "-loop", "0"};
    argv.insert(argv.end(), pictures.begin(), pictures.end());
    argv.insert(argv.end(), {"-layers", "Optimize", "animation.gif"});
    if (run_program(argv, folder.string(), log) != 0 || !fs::exists(folder / "animation.gif"))
      throw RunError("convert (ImageMagick) failed to make animation.gif; see " + log);
    summary.animation = (folder / "animation.gif").string();
  } else if (s.animation == "mp4") {
    const std::vector<std::string> argv = {
        "ffmpeg",        "-y",         "-loglevel",
        "error",         "-framerate", fmt::format("{}", s.fps),
        "-pattern_type", "glob",       "-i",
        "frame_*.png",   "-vf",        "scale=trunc(iw/2)*2:trunc(ih/2)*2",
        "-pix_fmt",      "yuv420p",    "animation.mp4"};
    if (run_program(argv, folder.string(), log) != 0 || !fs::exists(folder / "animation.mp4"))
      throw RunError("ffmpeg failed to make animation.mp4; see " + log);
    summary.animation = (folder / "animation.mp4").string();
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace fissure
