#include "fictitious/clamped_images.hpp"

#include <Eigen/Dense>
#include <stdexcept>
#include <utility>
#include <vector>

#include "scene/point_cloud.hpp"

namespace fissure::bench {

void clamp_stencils(const Particles& particles, double horizon, double fit_radius, double clamp_x,
                    FictitiousParticles& images) {
  using Vec3 = Eigen::Vector3d;
  using Basis = Eigen::Matrix<double, 4, 1>;
  const PointCloud cloud{particles.reference};
  KdTree points(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  points.buildIndex();
  FictitiousParticles out = images;
  out.offsets.assign(1, 0);
  out.particle.clear();
  out.weight.clear();
  std::vector<std::pair<std::uint32_t, double>> matches;
  for (int g = 0; g < images.count(); ++g) {
    const Vec3 x(images.position[3 * g], images.position[3 * g + 1], images.position[3 * g + 2]);
    if (x[0] >= clamp_x) {
      for (int s = images.offsets[g]; s < images.offsets[g + 1]; ++s)
        out.particle.push_back(images.particle[s]), out.weight.push_back(images.weight[s]);
      out.offsets.push_back(static_cast<int>(out.particle.size()));
      continue;
    }
    std::uint32_t k;
    double squared;
    points.knnSearch(x.data(), 1, &k, &squared);
    const Vec3 xk(particles.reference[3 * k], particles.reference[3 * k + 1],
                  particles.reference[3 * k + 2]);
    // φ(p) = (p_x − x_c)/δ · (1, (p − x_k)/δ): every quadratic that vanishes on the face
    auto basis = [&](const Vec3& p) {
      const Vec3 d = (p - xk) / horizon;
      Basis phi;
      phi << 1, d[0], d[1], d[2];
      return Basis((p[0] - clamp_x) / horizon * phi);
    };
    const double radius = fit_radius * horizon;
    points.radiusSearch(xk.data(), radius * radius, matches, nanoflann::SearchParams(32, 0, false));
    Eigen::Matrix4d moments = Eigen::Matrix4d::Zero();
    std::vector<std::pair<int, Basis>> rows;
    for (const auto& m : matches) {
      const int j = static_cast<int>(m.first);
      const Vec3 p(particles.reference[3 * j], particles.reference[3 * j + 1],
                   particles.reference[3 * j + 2]);
      const double distance = (p - xk).norm();
      const double weight = (distance > 0 ? horizon / distance : 1.0) * particles.volume[j];
      const Basis phi = basis(p);
      moments += weight * phi * phi.transpose();
      rows.push_back({j, weight * phi});
    }
    const Eigen::LDLT<Eigen::Matrix4d> fit(moments);
    if (rows.size() < 4 || fit.info() != Eigen::Success || !fit.isPositive() ||
        fit.vectorD().minCoeff() <= 1e-12 * fit.vectorD().maxCoeff())
      throw std::invalid_argument("clamped images: the fit around a particle is singular");
    const Basis z = fit.solve(basis(x));
    for (const auto& [j, phi] : rows) out.particle.push_back(j), out.weight.push_back(phi.dot(z));
    out.offsets.push_back(static_cast<int>(out.particle.size()));
  }
  images = std::move(out);
}

}  // namespace fissure::bench
