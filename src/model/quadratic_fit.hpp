#pragma once
// The weighted least-squares quadratic fit that moves fictitious particles
// (fictitious_particles.hpp) and that the second-order correction fits over each
// family (docs/model.md, deviation 8): differences of a field around a point x_0,
//   f(x_0 + ξ_j) − f(x_0) ≈ Σ_m q_m φ_m(ξ_j / s),
//   φ(d) = (d_x, d_y, d_z, ½d_x², ½d_y², ½d_z², d_xd_y, d_xd_z, d_yd_z),
// so that q_0..2 = s ∇f and q_3..8 = s² (∂²f/∂x², ∂²f/∂y², ∂²f/∂z², ∂²f/∂x∂y, ∂²f/∂x∂z,
// ∂²f/∂y∂z) at x_0 when f is quadratic. The scale s (a horizon) keeps the entries of one size.
#include <Eigen/Core>
#include <vector>

namespace fissure {

using QuadraticBasis = Eigen::Matrix<double, 9, 1>;

// The index m of q_m, the coefficient of ∂²f/∂x_k∂x_l, in that basis.
inline constexpr int kSecondDerivative[3][3] = {{3, 6, 7}, {6, 4, 8}, {7, 8, 5}};

QuadraticBasis quadratic_basis(const Eigen::Vector3d& xi, double scale);

// Per point ξ_j the coefficients a_j with q = Σ_j a_j (f_j − f_0), minimising
// Σ_j weight_j (f_j − f_0 − q·φ(ξ_j/s))². False, and coefficients left empty, when the points do
// not determine a quadratic: fewer than 9, or too close to a plane or a quadric for the fit's
// moments to be invertible (smallest pivot under 1e-12 of the largest).
bool quadratic_fit(const std::vector<Eigen::Vector3d>& xi, const std::vector<double>& weight,
                   double scale, std::vector<QuadraticBasis>& coefficients);

}  // namespace fissure
