// The files a run writes (docs/output.md), read back from a real `fissure run` of a tiny scene:
// particles.pvd, the VTU frames (binary appended layout), probes.csv and summary.json; and the
// lines `fissure info` prints.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "app/run_fissure.hpp"
#include "scene/config.hpp"
#include "scene/scene.hpp"
#include "support/csv.hpp"

namespace fissure {
namespace {

namespace fs = std::filesystem;

// 21 steps of exactly 1 ms (end is a multiple of dt), frames every 5 ms (t = 0 … 0.020: 5
// frames) plus the final frame at the end (0.021), probe rows every 2 ms (t = 0 … 0.020: 11)
// plus the row at the end (0.021): 12 rows. Soft material so 1 ms is under the stable step.
const char* kScene =
    "name: tiny\n"
    "time: {end: 0.021, dt: 0.001}\n"
    "gravity: [0, 0, -9.81]\n"
    "bodies:\n"
    "  - geometry: {box: {min: [0, 0, 0], max: [0.08, 0.04, 0.04]}}\n"
    "    resolution: 0.02\n"
    "    material: {density: 1000, bulk_modulus: 2.0e3, shear_modulus: 2.0e3}\n"
    "constraints:\n"
    "  - {region: {box: {min: [-1, -1, -1], max: [0.02, 1, 1]}}, fix: true}\n"
    "probes:\n"
    "  - {name: tip, region: {box: {min: [0.06, -1, -1], max: [1, 1, 1]}}}\n"
    "  - {name: base, region: {sphere: {center: [0, 0.02, 0.02], radius: 0.04}}}\n"
    "output: {every: 0.005, probe_every: 0.002}\n";
constexpr int kSteps = 21;
constexpr double kDt = 0.001, kEvery = 0.005, kProbeEvery = 0.002, kEnd = 0.021;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream s(text);
  for (std::string line; std::getline(s, line);) lines.push_back(line);
  return lines;
}

// A JSON number, as the grammar defines it (so "nan", "inf" or "1." are rejected).
bool is_json_number(const std::string& token) {
  static const std::regex number(R"(-?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?)");
  return std::regex_match(token, number);
}

// The keys of the `summary.json` table in docs/output.md (first column, in backticks).
std::vector<std::string> documented_summary_keys() {
  const auto lines = lines_of(test::slurp(fs::path(FISSURE_SOURCE_DIR) / "docs" / "output.md"));
  std::vector<std::string> keys;
  bool in_section = false;
  static const std::regex row(R"(^\|\s*`([A-Za-z_]+)`\s*\|)");
  for (const auto& line : lines) {
    if (line.rfind("## ", 0) == 0) in_section = line.find("summary.json") != std::string::npos;
    std::smatch m;
    if (in_section && std::regex_search(line, m, row)) keys.push_back(m[1]);
  }
  return keys;
}

struct DataArray {
  std::string type, name;
  int components = 0;
  std::uint64_t offset = 0;
};

struct Vtu {
  long points = -1;
  std::map<std::string, std::vector<double>> float64;  // Float64 arrays by name
  std::map<std::string, std::vector<std::int32_t>> int32;
};

std::string attribute(const std::string& element, const std::string& name) {
  const std::regex re("\\b" + name + "=\"([^\"]*)\"");
  std::smatch m;
  return std::regex_search(element, m, re) ? std::string(m[1]) : std::string();
}

// Parses a VTU written with appended raw data and UInt64 block headers, checking as it goes
// that every block's byte count is NumberOfPoints × components × type size and that the blocks
// tile the appended section exactly.
Vtu read_vtu(const fs::path& path) {
  Vtu vtu;
  const std::string text = test::slurp(path);
  const std::string marker = "<AppendedData encoding=\"raw\">";
  const auto at = text.find(marker);
  EXPECT_NE(at, std::string::npos) << path;
  if (at == std::string::npos) return vtu;
  const auto underscore = text.find('_', at + marker.size());
  EXPECT_NE(underscore, std::string::npos) << path;
  if (underscore == std::string::npos) return vtu;
  // Only whitespace between the tag and the '_' that starts the data.
  for (auto k = at + marker.size(); k < underscore; ++k) {
    EXPECT_TRUE(std::isspace(static_cast<unsigned char>(text[k])));
  }
  const std::string header = text.substr(0, at);
  EXPECT_NE(header.find("header_type=\"UInt64\""), std::string::npos) << path;
  EXPECT_NE(header.find("byte_order=\"LittleEndian\""), std::string::npos) << path;
  std::smatch m;
  if (!std::regex_search(header, m, std::regex(R"re(<Piece[^>]*NumberOfPoints="([0-9]+)")re"))) {
    ADD_FAILURE() << "no NumberOfPoints in " << path;
    return vtu;
  }
  vtu.points = std::stol(m[1]);
  std::vector<DataArray> arrays;
  const std::regex element(R"(<DataArray[^>]*>)");
  for (auto it = std::sregex_iterator(header.begin(), header.end(), element);
       it != std::sregex_iterator(); ++it) {
    const std::string e = it->str();
    EXPECT_EQ(attribute(e, "format"), "appended") << e;
    const std::string components = attribute(e, "NumberOfComponents");
    arrays.push_back({attribute(e, "type"), attribute(e, "Name"),
                      components.empty() ? 1 : std::stoi(components),
                      std::stoull(attribute(e, "offset"))});
  }
  const std::size_t data = underscore + 1;
  std::uint64_t expected_offset = 0;
  for (const auto& a : arrays) {
    const std::size_t size = a.type == "Float64" ? 8
                             : a.type == "Int32" ? 4
                             : a.type == "UInt8" ? 1
                                                 : 0;
    EXPECT_NE(size, 0u) << "unexpected type " << a.type << " of " << a.name;
    // Blocks follow one another: each offset is where the previous block ended.
    EXPECT_EQ(a.offset, expected_offset) << a.name << " in " << path;
    if (data + a.offset + 8 > text.size()) {
      ADD_FAILURE() << a.name << " block starts past the end of " << path;
      return vtu;
    }
    std::uint64_t bytes;
    std::memcpy(&bytes, text.data() + data + a.offset, 8);
    const std::uint64_t expected = static_cast<std::uint64_t>(vtu.points) * a.components * size;
    EXPECT_EQ(bytes, expected) << a.name << " in " << path;
    if (bytes != expected || data + a.offset + 8 + bytes > text.size()) return vtu;
    const char* begin = text.data() + data + a.offset + 8;
    if (a.type == "Float64") {
      std::vector<double> v(bytes / 8);
      std::memcpy(v.data(), begin, bytes);
      vtu.float64[a.name] = std::move(v);
    } else if (a.type == "Int32") {
      std::vector<std::int32_t> v(bytes / 4);
      std::memcpy(v.data(), begin, bytes);
      vtu.int32[a.name] = std::move(v);
    }
    expected_offset = a.offset + 8 + bytes;
  }
  EXPECT_EQ(text.substr(data + expected_offset), "\n</AppendedData>\n</VTKFile>\n") << path;
  return vtu;
}

struct RunFiles {
  fs::path dir, yaml, out;
  test::Outcome outcome;
};

// One run shared by the tests (a run is ~0.1 s, but there is no reason to repeat it).
const RunFiles& tiny_run() {
  static const RunFiles run = [] {
    RunFiles r;
    r.dir = test::scratch_dir("output");
    r.yaml = r.dir / "tiny.yaml";
    r.out = r.dir / "out";
    test::write_file(r.yaml, kScene);
    r.outcome = test::run_fissure("run " + r.yaml.string() + " --out " + r.out.string());
    return r;
  }();
  return run;
}

TEST(Output, PvdListsEveryFrameWithIncreasingTime) {
  const RunFiles& run = tiny_run();
  ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  const std::string pvd = test::slurp(run.out / "particles.pvd");
  const std::regex dataset(R"(<DataSet[^>]*>)");
  std::vector<double> times;
  std::set<std::string> listed;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), dataset);
       it != std::sregex_iterator(); ++it) {
    const std::string e = it->str();
    times.push_back(std::stod(attribute(e, "timestep")));
    const std::string file = attribute(e, "file");
    EXPECT_TRUE(fs::exists(run.out / file)) << file;
    listed.insert(file);
  }
  // Frames at t = 0, 5, 10, 15, 20 ms and the final one at 21 ms: the step times are sums of
  // 1 ms steps and printed with 9 significant digits, so 1e-9 s is far above their round-off
  // and far below a step.
  ASSERT_EQ(times.size(), 6u) << pvd;
  ASSERT_EQ(listed.size(), times.size()) << "a file is listed twice";
  for (std::size_t k = 0; k < times.size(); ++k) {
    EXPECT_NEAR(times[k], k < 5 ? k * kEvery : kEnd, 1e-9);
    if (k > 0) {
      EXPECT_GT(times[k], times[k - 1]);
    }
  }
  // And no frame on disk is left out of the index.
  for (const auto& entry : fs::directory_iterator(run.out)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() == ".vtu") {
      EXPECT_TRUE(listed.count(name)) << name << " not in the .pvd";
    }
  }
}

TEST(Output, VtuFramesParseAndMatchTheRun) {
  const RunFiles& run = tiny_run();
  ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  const auto summary = test::read_summary(run.out / "summary.json");
  ASSERT_TRUE(summary.count("particles"));
  const long particles = std::stol(summary.at("particles"));
  ASSERT_GT(particles, 0);
  std::vector<double> reference;
  for (int frame = 0; frame < 5; ++frame) {
    const fs::path file = run.out / fmt::format("particles_{:06d}.vtu", frame);
    SCOPED_TRACE(file.string());
    const Vtu vtu = read_vtu(file);
    ASSERT_FALSE(HasFailure());
    EXPECT_EQ(vtu.points, particles);
    for (const char* name : {"position", "displacement", "velocity", "damage", "dilatation"})
      ASSERT_TRUE(vtu.float64.count(name)) << name;
    for (const char* name : {"connectivity", "offsets", "body"})
      ASSERT_TRUE(vtu.int32.count(name)) << name;
    const auto& y = vtu.float64.at("position");
    const auto& u = vtu.float64.at("displacement");
    // One vertex cell per particle: connectivity i, offsets i + 1 (exact integers).
    for (long i = 0; i < particles; ++i) {
      ASSERT_EQ(vtu.int32.at("connectivity")[i], i);
      ASSERT_EQ(vtu.int32.at("offsets")[i], i + 1);
      ASSERT_EQ(vtu.int32.at("body")[i], 0);
    }
    if (frame == 0) {
      // At t = 0 the positions are the reference ones: y − x is exactly 0, and the body
      // starts at rest (no velocity key, and the fixed constraint assigns 0).
      for (double d : u) ASSERT_EQ(d, 0.0);
      for (double v : vtu.float64.at("velocity")) ASSERT_EQ(v, 0.0);
      reference = y;
    } else {
      // y − (y − x) recovers x to round-off of one subtraction of numbers ~0.1 m: 1e-12 m.
      double moved = 0;
      for (std::size_t k = 0; k < y.size(); ++k) {
        ASSERT_NEAR(y[k] - u[k], reference[k], 1e-12);
        moved = std::max(moved, std::abs(u[k]));
      }
      EXPECT_GT(moved, 0.0) << "under gravity the free end moves";
    }
  }
}

// With fracture the frames carry the particles' damage φ = 1 − n_i/N_i: a plane crack through
// a block damages the particles next to it (0 < φ ≤ 1) from frame 0 on, leaves the far ones
// intact, and summary.json counts the cut bonds.
TEST(Output, VtuDamageFollowsTheFracture) {
  const auto dir = test::scratch_dir("output_damage");
  test::write_file(dir / "scene.yaml",
                   "time: {end: 0.002, dt: 0.001}\nbodies:\n"
                   "  - geometry: {box: {min: [0, 0, 0], max: [0.2, 0.1, 0.1]}}\n"
                   "    resolution: 0.025\n    material: {density: 1000, bulk_modulus: 2.0e3, "
                   "shear_modulus: 2.0e3, fracture: {critical_stretch: 1}}\n"
                   "initial_cracks:\n  - {plane: {point: [0.1, 0, 0], normal: [1, 0, 0]}}\n"
                   "output: {every: 0.001}\n");
  const auto outcome = test::run_fissure("run " + (dir / "scene.yaml").string() + " --out " +
                                         (dir / "out").string());
  ASSERT_EQ(outcome.exit_code, 0) << outcome.output;
  EXPECT_GT(std::stol(test::read_summary(dir / "out" / "summary.json").at("broken_bonds")), 0);
  const Vtu vtu = read_vtu(dir / "out" / "particles_000000.vtu");
  ASSERT_FALSE(HasFailure());
  const auto& damage = vtu.float64.at("damage");
  const auto& y = vtu.float64.at("position");
  double near = 0, far = 0;
  for (std::size_t i = 0; i < damage.size(); ++i) {
    ASSERT_GE(damage[i], 0.0);
    ASSERT_LE(damage[i], 1.0);
    if (std::abs(y[3 * i] - 0.1) < 0.01) near = std::max(near, damage[i]);
    if (std::abs(y[3 * i] - 0.1) > 0.06) far = std::max(far, damage[i]);
  }
  EXPECT_GT(near, 0.2);  // about half of a family lies across the crack
  EXPECT_EQ(far, 0.0);   // beyond the horizon (0.036 m) of the crack nothing is cut
}

TEST(Output, ProbesCsvHeaderAndRows) {
  const RunFiles& run = tiny_run();
  ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  const auto lines = lines_of(test::slurp(run.out / "probes.csv"));
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0],
            "time,kinetic_energy,elastic_energy,"
            "tip.pos_x,tip.pos_y,tip.pos_z,tip.disp_x,tip.disp_y,tip.disp_z,"
            "base.pos_x,base.pos_y,base.pos_z,base.disp_x,base.disp_y,base.disp_z,"
            "gravity_work,constraint_work,collider_work,damping_loss,contact_loss,"
            "plastic_dissipation,fracture_release,balance_error,stored_energy");
  std::vector<double> expected_times;
  for (int k = 0; k * kProbeEvery <= kEnd - 0.5 * kDt; ++k)
    expected_times.push_back(k * kProbeEvery);
  expected_times.push_back(kEnd);  // the end is not a multiple of probe_every: one more row
  ASSERT_EQ(lines.size() - 1, expected_times.size());
  std::vector<std::vector<double>> rows;
  for (std::size_t r = 1; r < lines.size(); ++r) {
    std::vector<double> v;
    for (const std::string& cell : test::csv_cells(lines[r])) {
      std::size_t used = 0;
      v.push_back(std::stod(cell, &used));
      EXPECT_EQ(used, cell.size()) << cell;
    }
    ASSERT_EQ(v.size(), 24u) << lines[r];
    // Sums of 1 ms steps, printed to 9 significant digits: within 1e-9 s of the multiple.
    EXPECT_NEAR(v[0], expected_times[r - 1], 1e-9) << lines[r];
    if (r > 1) {
      EXPECT_GT(v[0], rows.back()[0]);
    }
    rows.push_back(v);
  }
  // Row 0 is the reference state at rest: zero kinetic energy and displacement, exactly.
  EXPECT_EQ(rows[0][1], 0.0);
  for (int c : {6, 7, 8, 12, 13, 14}) EXPECT_EQ(rows[0][c], 0.0) << "column " << c;

  // The tip probe's mean displacement at t = 20 ms is the mean of the VTU displacements of the
  // particles with reference x ≥ 0.06 in frame 4 (t = 20 ms): the same numbers, printed with 9
  // significant digits, so they agree to 1e-8 relative.
  const Vtu vtu = read_vtu(run.out / "particles_000004.vtu");
  ASSERT_FALSE(HasFailure());
  const auto& y = vtu.float64.at("position");
  const auto& u = vtu.float64.at("displacement");
  double mean[3] = {0, 0, 0};
  int members = 0;
  for (long i = 0; i < vtu.points; ++i)
    if (y[3 * i] - u[3 * i] >= 0.06) {
      ++members;
      for (int k = 0; k < 3; ++k) mean[k] += u[3 * i + k];
    }
  ASSERT_GT(members, 0);
  const auto& row = rows[10];
  ASSERT_NEAR(row[0], 0.020, 1e-9);
  for (int k = 0; k < 3; ++k) {
    mean[k] /= members;
    EXPECT_NEAR(row[6 + k], mean[k], 1e-8 * std::abs(mean[k]) + 1e-15) << "tip.disp " << k;
  }
  EXPECT_LT(mean[2], 0.0) << "the free end sags under gravity";
}

TEST(Output, SummaryHasEveryDocumentedKey) {
  const RunFiles& run = tiny_run();
  ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  const std::string text = test::slurp(run.out / "summary.json");
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.front(), '{');
  EXPECT_EQ(text[text.find_last_not_of(" \n")], '}');
  const auto values = test::read_summary(run.out / "summary.json");
  const auto keys = documented_summary_keys();
  // Guard the doc parser itself: the table lists at least these.
  for (const char* k : {"status", "particles", "bonds", "steps", "dt", "energy_drift"})
    EXPECT_NE(std::find(keys.begin(), keys.end(), k), keys.end())
        << k << " not found in docs/output.md";
  for (const auto& key : keys) {
    ASSERT_TRUE(values.count(key)) << "summary.json lacks documented key " << key << "\n" << text;
    if (key == "status") {
      EXPECT_EQ(values.at(key), "\"completed\"");
    } else if (key == "integrator") {
      EXPECT_EQ(values.at(key), "\"symplectic_euler\"");
    } else if (key == "integrator_statistics" || key == "model_statistics" || key == "energy") {
      EXPECT_EQ(values.at(key).front(), '{');
    } else if (key == "message") {
      EXPECT_EQ(values.at(key), "\"\"");
    } else {
      EXPECT_TRUE(is_json_number(values.at(key))) << key << " = " << values.at(key);
    }
  }
  for (const auto& [key, value] : values)
    EXPECT_NE(std::find(keys.begin(), keys.end(), key), keys.end()) << key << " is not documented";

  // Exact integers and the fixed step.
  EXPECT_EQ(std::stol(values.at("steps")), kSteps);
  EXPECT_DOUBLE_EQ(std::stod(values.at("dt")), kDt);  // printed with 9 digits: 0.001 exactly
  const Scene scene = build_scene(load_config(run.yaml.string()));
  EXPECT_EQ(std::stol(values.at("particles")), scene.particles.count());
  EXPECT_EQ(2 * std::stol(values.at("bonds")), static_cast<long>(scene.families.directed_bonds()));
}

TEST(Output, InfoPrintsTheDocumentedLines) {
  const RunFiles& run = tiny_run();
  const auto outcome = test::run_fissure("info " + run.yaml.string());
  ASSERT_EQ(outcome.exit_code, 0) << outcome.output;
  const auto lines = lines_of(outcome.output);
  const Scene scene = build_scene(load_config(run.yaml.string()));
  std::map<std::string, std::string> found;
  int effects = 0;
  for (const auto& line : lines) {
    for (const char* prefix :
         {"particles: ", "bonds: ", "bytes per bond: ", "stable dt estimate: "})
      if (line.rfind(prefix, 0) == 0) found[prefix] = line.substr(std::strlen(prefix));
    if (line.rfind("effects:", 0) == 0) {
      ++effects;
      EXPECT_EQ(line, "effects: elasticity");
    }
  }
  EXPECT_EQ(effects, 1) << outcome.output;
  ASSERT_EQ(found.size(), 4u) << outcome.output;
  // The counts are the scene's, exactly.
  EXPECT_EQ(std::stol(found["particles: "]), scene.particles.count());
  EXPECT_EQ(2 * std::stol(found["bonds: "]), static_cast<long>(scene.families.directed_bonds()));
  EXPECT_GT(std::stol(found["bytes per bond: "]), 0);
  // The estimate is printed with 4 significant digits: it matches summary.json's stable_dt
  // (9 digits) to 5e-4 relative.
  const double info_dt = std::stod(found["stable dt estimate: "]);
  if (run.outcome.exit_code == 0) {
    const double summary_dt =
        std::stod(test::read_summary(run.out / "summary.json").at("stable_dt"));
    EXPECT_NEAR(info_dt, summary_dt, 5e-4 * summary_dt);
  }
}

}  // namespace
}  // namespace fissure
