#include "model/fictitious_particles.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

#include "model/quadratic_fit.hpp"
#include "scene/point_cloud.hpp"

namespace fissure {

namespace {

using Vec3 = Eigen::Vector3d;

Vec3 corner(const Triangle& t, int c) { return {t[3 * c], t[3 * c + 1], t[3 * c + 2]}; }

// The point of triangle abc closest to p, by the Voronoi region of p (vertex, edge or face).
Vec3 closest_point(const Vec3& p, const Triangle& t) {
  const Vec3 a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denominator = 1 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

struct Plane {
  Vec3 normal, point;
};

// Kept images in cells of edge h, to find one within h of a point.
class ImageGrid {
 public:
  explicit ImageGrid(double h) : h_(h) {}
  bool near(const Vec3& x, const std::vector<double>& position) const {
    const auto c = cell(x);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key(c[0] + dx, c[1] + dy, c[2] + dz));
          if (it == cells_.end()) continue;
          for (int g : it->second)
            if ((Vec3(position[3 * g], position[3 * g + 1], position[3 * g + 2]) - x).norm() < h_)
              return true;
        }
    return false;
  }
  void add(const Vec3& x, int g) {
    const auto c = cell(x);
    cells_[key(c[0], c[1], c[2])].push_back(g);
  }

 private:
  std::array<std::int64_t, 3> cell(const Vec3& x) const {
    return {static_cast<std::int64_t>(std::floor(x[0] / h_)),
            static_cast<std::int64_t>(std::floor(x[1] / h_)),
            static_cast<std::int64_t>(std::floor(x[2] / h_))};
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (std::uint64_t(x) & 0x1fffff) | (std::uint64_t(y) & 0x1fffff) << 21 |
           (std::uint64_t(z) & 0x1fffff) << 42;
  }
  double h_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

// The distinct faces of the boundary within δ of x: the plane of the nearest triangle of each,
// nearest first. A triangle is part of an accepted face when their planes are parallel within
// kSameFaceCosine (either orientation) and its closest point lies within `thickness` of that
// face's plane; the two faces of a plate thinner than 2δ stay distinct.
std::vector<Plane> faces_near(const Vec3& x, const std::vector<Triangle>& boundary,
                              const KdTree& centroids, double search_radius, double horizon,
                              double thickness) {
  std::vector<std::pair<std::uint32_t, double>> matches;
  centroids.radiusSearch(x.data(), search_radius * search_radius, matches,
                         nanoflann::SearchParams(32, 0, false));
  std::vector<std::pair<double, Plane>> candidates;
  for (const auto& match : matches) {
    const Triangle& t = boundary[match.first];
    const Vec3 q = closest_point(x, t);
    const double distance = (q - x).norm();
    if (distance >= horizon) continue;
    const Vec3 n = (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0));
    if (n.norm() == 0) continue;  // a degenerate triangle has no plane
    candidates.push_back({distance, {n.normalized(), q}});
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Plane> faces;
  for (const auto& [distance, plane] : candidates) {
    bool same = false;
    for (const Plane& f : faces)
      same = same || (std::abs(f.normal.dot(plane.normal)) > kSameFaceCosine &&
                      std::abs((plane.point - f.point).dot(f.normal)) < thickness);
    if (!same) faces.push_back(plane);
  }
  return faces;
}

Vec3 reflect(const Vec3& x, const Plane& p) {
  return x - 2 * (x - p.point).dot(p.normal) * p.normal;
}

// The particle of `body` nearest to x within 2 horizons, or −1.
int nearest_of_body(const KdTree& points, const Particles& particles, const Vec3& x, int body,
                    double horizon) {
  std::vector<std::pair<std::uint32_t, double>> matches;
  points.radiusSearch(x.data(), 4 * horizon * horizon, matches,
                      nanoflann::SearchParams(32, 0, true));
  for (const auto& m : matches)
    if (particles.body[m.first] == body) return static_cast<int>(m.first);
  return -1;
}

}  // namespace

void add_mirror_images(const Particles& particles, int body, const std::vector<Triangle>& boundary,
                       double horizon, FictitiousParticles& images) {
  if (boundary.empty()) return;
  double mean_volume = 0;
  int members = 0;
  for (int i = 0; i < particles.count(); ++i)
    if (particles.body[i] == body) mean_volume += particles.volume[i], ++members;
  if (members == 0) return;
  const double spacing = std::cbrt(mean_volume / members), gap = 0.5 * spacing;

  std::vector<double> centroid(3 * boundary.size());
  double reach = 0;  // the farthest corner from its triangle's centroid
  for (std::size_t t = 0; t < boundary.size(); ++t) {
    const Vec3 c = (corner(boundary[t], 0) + corner(boundary[t], 1) + corner(boundary[t], 2)) / 3;
    for (int a = 0; a < 3; ++a) centroid[3 * t + a] = c[a];
    for (int k = 0; k < 3; ++k) reach = std::max(reach, (corner(boundary[t], k) - c).norm());
  }
  const PointCloud triangle_cloud{centroid}, particle_cloud{particles.reference};
  KdTree triangles(3, triangle_cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  KdTree points(3, particle_cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  triangles.buildIndex();
  points.buildIndex();
  ImageGrid grid(gap);
  for (int g = 0; g < images.count(); ++g)
    grid.add(Vec3(images.position[3 * g], images.position[3 * g + 1], images.position[3 * g + 2]),
             g);

  std::vector<std::pair<std::uint32_t, double>> matches;
  for (int s = 0; s < particles.count(); ++s) {
    if (particles.body[s] != body) continue;
    const Vec3 x(particles.reference[3 * s], particles.reference[3 * s + 1],
                 particles.reference[3 * s + 2]);
    const std::vector<Plane> faces =
        faces_near(x, boundary, triangles, horizon + reach, horizon, gap);
    const int count = std::min<int>(static_cast<int>(faces.size()), 3);
    for (int subset = 1; subset < (1 << count); ++subset) {
      Vec3 image = x;
      for (int f = 0; f < count; ++f)
        if (subset & (1 << f)) image = reflect(image, faces[f]);
      std::uint32_t nearest;
      double squared;
      points.knnSearch(image.data(), 1, &nearest, &squared);
      if (squared < gap * gap || grid.near(image, images.position)) continue;
      points.radiusSearch(image.data(), horizon * horizon, matches,
                          nanoflann::SearchParams(32, 0, false));
      const bool in_a_family = std::any_of(matches.begin(), matches.end(), [&](const auto& m) {
        return particles.body[m.first] == body;
      });
      if (!in_a_family) continue;
      grid.add(image, images.count());
      images.position.insert(images.position.end(), image.data(), image.data() + 3);
      images.volume.push_back(particles.volume[s]);
      images.body.push_back(body);
    }
  }
}

void fit_stencils(const Particles& particles, const std::vector<double>& horizon_of_body,
                  double fit_radius, FictitiousParticles& images) {
  const PointCloud cloud{particles.reference};
  KdTree points(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  points.buildIndex();
  const int count = images.count();
  std::vector<std::vector<std::pair<int, double>>> stencil(count);
  std::vector<std::string> failure(count);
#pragma omp parallel for schedule(dynamic, 16)
  for (int g = 0; g < count; ++g) {
    const int body = images.body[g];
    const double horizon = horizon_of_body[body], radius = fit_radius * horizon;
    const Vec3 x(images.position[3 * g], images.position[3 * g + 1], images.position[3 * g + 2]);
    const int k = nearest_of_body(points, particles, x, body, horizon);
    if (k < 0) {
      failure[g] = fmt::format("image {} has no particle of body {} within 2 horizons", g, body);
      continue;
    }
    const Vec3 xk(particles.reference[3 * k], particles.reference[3 * k + 1],
                  particles.reference[3 * k + 2]);
    std::vector<std::pair<std::uint32_t, double>> matches;
    points.radiusSearch(xk.data(), radius * radius, matches, nanoflann::SearchParams(32, 0, false));
    std::vector<int> members;
    std::vector<Vec3> xi;
    std::vector<double> weight;
    for (const auto& m : matches) {
      const int j = static_cast<int>(m.first);
      if (j == k || particles.body[j] != body) continue;
      const Vec3 d = Vec3(particles.reference[3 * j], particles.reference[3 * j + 1],
                          particles.reference[3 * j + 2]) -
                     xk;
      members.push_back(j), xi.push_back(d),
          weight.push_back(horizon / d.norm() * particles.volume[j]);
    }
    std::vector<QuadraticBasis> a;
    if (!quadratic_fit(xi, weight, horizon, a)) {
      failure[g] = fmt::format(
          "the displacement around particle {} cannot be fitted: {} particles of its body within "
          "{:.3g} m (a quadratic needs 9 spread in 3 dimensions)",
          k, members.size(), radius);
      continue;
    }
    const QuadraticBasis at_image = quadratic_basis(x - xk, horizon);
    double sum = 0;
    for (std::size_t r = 0; r < members.size(); ++r) {
      const double w = a[r].dot(at_image);
      stencil[g].push_back({members[r], w});
      sum += w;
    }
    stencil[g].push_back({k, 1 - sum});  // u_g = u_k + Σ_j w_j (u_j − u_k)
  }
  for (const std::string& f : failure)
    if (!f.empty()) throw std::invalid_argument("fictitious particles: " + f);
  images.offsets.assign(1, 0);
  images.particle.clear();
  images.weight.clear();
  for (const auto& s : stencil) {
    for (const auto& [j, w] : s) images.particle.push_back(j), images.weight.push_back(w);
    images.offsets.push_back(static_cast<int>(images.particle.size()));
  }
}

void clamp_stencils(const Particles& particles, const std::vector<double>& horizon_of_body,
                    double fit_radius, const ClampPlane& plane, FictitiousParticles& images) {
  const PointCloud cloud{particles.reference};
  KdTree points(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  points.buildIndex();
  const Vec3 origin(plane.point.data()), normal = Vec3(plane.normal.data()).normalized();
  FictitiousParticles out = images;
  out.offsets.assign(1, 0);
  out.particle.clear();
  out.weight.clear();
  std::vector<std::pair<std::uint32_t, double>> matches;
  for (int g = 0; g < images.count(); ++g) {
    const Vec3 x(images.position[3 * g], images.position[3 * g + 1], images.position[3 * g + 2]);
    if (normal.dot(x - origin) <= 0) {
      for (int s = images.offsets[g]; s < images.offsets[g + 1]; ++s)
        out.particle.push_back(images.particle[s]), out.weight.push_back(images.weight[s]);
      out.offsets.push_back(static_cast<int>(out.particle.size()));
      continue;
    }
    const int body = images.body[g];
    const double horizon = horizon_of_body[body], radius = fit_radius * horizon;
    const int k = nearest_of_body(points, particles, x, body, horizon);
    if (k < 0)
      throw std::invalid_argument(fmt::format(
          "fictitious particles: image {} has no particle of body {} within 2 horizons", g, body));
    const Vec3 xk(particles.reference[3 * k], particles.reference[3 * k + 1],
                  particles.reference[3 * k + 2]);
    // φ(p) = (n·(p − point))/δ (1, (p − x_k)/δ): every quadratic vanishing on the plane
    auto basis = [&](const Vec3& p) {
      const Vec3 d = (p - xk) / horizon;
      return Eigen::Vector4d(Eigen::Vector4d(1, d[0], d[1], d[2]) * normal.dot(p - origin) /
                             horizon);
    };
    points.radiusSearch(xk.data(), radius * radius, matches, nanoflann::SearchParams(32, 0, false));
    Eigen::Matrix4d moments = Eigen::Matrix4d::Zero();
    std::vector<std::pair<int, Eigen::Vector4d>> rows;
    for (const auto& m : matches) {
      const int j = static_cast<int>(m.first);
      if (particles.body[j] != body) continue;
      const Vec3 p(particles.reference[3 * j], particles.reference[3 * j + 1],
                   particles.reference[3 * j + 2]);
      const double distance = (p - xk).norm();
      const double weight = (distance > 0 ? horizon / distance : 1.0) * particles.volume[j];
      const Eigen::Vector4d phi = basis(p);
      moments += weight * phi * phi.transpose();  // Σ ω V_j φ φᵀ
      rows.push_back({j, weight * phi});
    }
    const Eigen::LDLT<Eigen::Matrix4d> fit(moments);
    if (rows.size() < 4 || fit.info() != Eigen::Success || !fit.isPositive() ||
        fit.vectorD().minCoeff() <= 1e-12 * fit.vectorD().maxCoeff())
      throw std::invalid_argument(fmt::format(
          "fictitious particles: the clamped displacement around particle {} cannot be fitted: "
          "{} particles of its body within {:.3g} m",
          k, rows.size(), radius));
    const Eigen::Vector4d z = fit.solve(basis(x));
    for (const auto& [j, phi] : rows) out.particle.push_back(j), out.weight.push_back(phi.dot(z));
    out.offsets.push_back(static_cast<int>(out.particle.size()));
  }
  images = std::move(out);
}

Particles with_images(const Particles& particles, const FictitiousParticles& images) {
  Particles extended = particles;
  for (int g = 0; g < images.count(); ++g) {
    extended.reference.insert(extended.reference.end(), &images.position[3 * g],
                              &images.position[3 * g + 3]);
    extended.velocity.insert(extended.velocity.end(), {0.0, 0.0, 0.0});
    extended.volume.push_back(images.volume[g]);
    extended.mass.push_back(0);
    extended.body.push_back(images.body[g]);
  }
  return extended;
}

std::array<double, 2> stencil_amplification(const FictitiousParticles& images) {
  double largest = 0, mean = 0;
  for (int g = 0; g < images.count(); ++g) {
    double sum = 0;
    for (int s = images.offsets[g]; s < images.offsets[g + 1]; ++s)
      sum += std::abs(images.weight[s]);
    largest = std::max(largest, sum);
    mean += sum / images.count();
  }
  return {largest, mean};
}

}  // namespace fissure
