// The nearest preconditioner's matrix (Stiffness::assemble_nearest_stiffness on
// linear/nearest_bonds.hpp's pattern): which bonds it keeps, that with every bond kept it is the
// majoriser, and that the rescaling of the kept bonds gives long waves the family's stiffness.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "linear/nearest_bonds.hpp"
#include "model/model.hpp"
#include "model/stiffness.hpp"
#include "support/stiffness_block.hpp"

namespace fissure {
namespace {

// The `members`-th smallest bond length of row i.
double reach(const Families& f, int i, int members) {
  std::vector<double> lengths(f.reference_length.begin() + f.offsets[i],
                              f.reference_length.begin() + f.offsets[i + 1]);
  std::sort(lengths.begin(), lengths.end());
  return lengths[std::min<std::size_t>(members, lengths.size()) - 1];
}

TEST(NearestStiffness, KeepsTheNearestMembersOfBothEnds) {
  const Scene scene = test::small_block();
  const Families& f = scene.families;
  constexpr int kMembers = 8;
  const std::vector<char> kept = nearest_bonds(f, kMembers);
  const SparseSymmetric pattern = nearest_bond_pattern(f, kept);
  const int n = static_cast<int>(f.offsets.size()) - 1;
  long kept_count = 0;
  for (int i = 0; i < n; ++i) {
    const double own = reach(f, i, kMembers);
    std::vector<int> members{i};
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      const int j = f.neighbors[b];
      const bool expected = f.reference_length[b] <= std::max(own, reach(f, j, kMembers));
      ASSERT_EQ(kept[b] != 0, expected) << "bond " << i << "-" << j;
      ASSERT_EQ(kept[b], kept[f.reverse[b]]);
      if (kept[b]) members.push_back(j), ++kept_count;
    }
    std::sort(members.begin(), members.end());
    // Row 3i + d holds the three columns of each kept member and of i itself, in order.
    for (int d = 0; d < 3; ++d) {
      const int row = 3 * i + d;
      ASSERT_EQ(pattern.offsets[row + 1] - pattern.offsets[row], 3 * members.size());
      for (std::size_t m = 0; m < members.size(); ++m)
        for (int e = 0; e < 3; ++e)
          ASSERT_EQ(pattern.columns[pattern.offsets[row] + 3 * m + e], 3 * members[m] + e);
    }
  }
  std::printf("nearest bonds: %ld of %zu directed bonds kept with %d members\n", kept_count,
              f.directed_bonds(), kMembers);
  EXPECT_LT(kept_count, static_cast<long>(f.directed_bonds()));
  EXPECT_GE(kept_count, static_cast<long>(kMembers) * n);
}

// With every bond kept every row's rescaling is 1, so the matrix is the majoriser's, bit for bit,
// in a general deformation (the geometric term included) with broken bonds.
TEST(NearestStiffness, EveryBondKeptIsTheMajoriser) {
  const Scene scene = test::small_block();
  auto model = make_model(scene);
  const Families& f = scene.families;
  for (int b = f.offsets[5]; b < f.offsets[6]; b += 2) {
    model->break_bond(5, b);
    model->break_bond(f.neighbors[b], f.reverse[b]);
  }
  const auto y = test::deformed(scene.particles, 0.02);
  const std::vector<char> kept = nearest_bonds(f, 1 << 20);
  SparseSymmetric near = nearest_bond_pattern(f, kept);
  SparseSymmetric majoriser = bond_pattern(f);
  ASSERT_EQ(near.offsets, majoriser.offsets);
  ASSERT_EQ(near.columns, majoriser.columns);
  model->stiffness()->assemble_nearest_stiffness(y.data(), kept, near);
  model->stiffness()->assemble_majoriser(y.data(), majoriser);
  EXPECT_EQ(near.values, majoriser.values);
}

// The nearest stiffness on the bonds `kept` and the majoriser, both at the reference state.
std::pair<SparseSymmetric, SparseSymmetric> at_rest(const Scene& scene,
                                                     const std::vector<char>& kept) {
  auto model = make_model(scene);
  const double* x = scene.particles.reference.data();
  SparseSymmetric near = nearest_bond_pattern(scene.families, kept);
  SparseSymmetric majoriser = bond_pattern(scene.families);
  model->stiffness()->assemble_nearest_stiffness(x, kept, near);
  model->stiffness()->assemble_majoriser(x, majoriser);
  return {std::move(near), std::move(majoriser)};
}

// Σ over the off-diagonal blocks (i, j) of −tr K_ij |x_j − x_i|²: at rest (no bond force, so no
// geometric term) −tr K_ij is the pair's bond stiffness k_ij, so this is the body's second moment
// of bond stiffness.
double second_moment(const SparseSymmetric& K, const std::vector<double>& x) {
  double sum = 0;
  for (int r = 0; r < K.rows; ++r)
    for (int k = K.offsets[r]; k < K.offsets[r + 1]; ++k) {
      const int c = K.columns[k];
      if (c % 3 != r % 3 || c / 3 == r / 3) continue;  // the diagonal of off-diagonal blocks
      const int i = r / 3, j = c / 3;
      double square = 0;
      for (int d = 0; d < 3; ++d) square += (x[3 * j + d] - x[3 * i + d]) * (x[3 * j + d] - x[3 * i + d]);
      sum -= K.values[k] * square;
    }
  return sum;
}

// The rescaling conserves the body's second moment exactly: summed over the kept directed bonds,
// ½(s_i + s_j) k_ij |ξ|² equals Σ_i s_i Σ_kept(i) k |ξ|² (k, |ξ| and the kept flags are the same
// both ways), which is Σ_i Σ_all(i) k |ξ|² by s_i's definition; so it holds to round-off (1e-12
// of ~10⁴ positive terms), where a rescaling off by a constant, or one missing, fails. The matrix
// is symmetric to round-off relative to its diagonal (the two rows multiply k n_r n_c in another
// order, and a diagonal block sums its family's bonds: measured 1.3e-16, bound 1e-14), which a
// rescaling by one end's s_i alone is not.
TEST(NearestStiffness, KeepsTheBodysSecondMomentOfBondStiffness) {
  const Scene scene = test::small_block();
  const Families& f = scene.families;
  const auto& x = scene.particles.reference;
  const std::vector<char> kept = nearest_bonds(f, 20);
  const auto [near, majoriser] = at_rest(scene, kept);
  long kept_count = 0;
  for (const char k : kept) kept_count += k;
  ASSERT_LT(kept_count, static_cast<long>(f.directed_bonds()));
  const double near_moment = second_moment(near, x), family_moment = second_moment(majoriser, x);
  std::printf("second moment of bond stiffness: nearest (%ld of %zu bonds) %.12e, majoriser %.12e\n",
              kept_count, f.directed_bonds(), near_moment, family_moment);
  EXPECT_NEAR(near_moment / family_moment, 1.0, 1e-12);
  double asymmetry = 0;
  for (int r = 0; r < near.rows; ++r)
    for (int k = near.offsets[r]; k < near.offsets[r + 1]; ++k) {
      const int c = near.columns[k];
      const double scale = std::sqrt(near.values[near.find(r, r)] * near.values[near.find(c, c)]);
      asymmetry = std::max(asymmetry, std::abs(near.values[k] - near.values[near.find(c, r)]) / scale);
    }
  std::printf("max |K_rc - K_cr| / sqrt(K_rr K_cc) = %.1e\n", asymmetry);
  EXPECT_LT(asymmetry, 1e-14);
}

// uᵀ K u for u = G x (G a strain) and for a bending field u_z = κ x²/2: what each deformation's
// stiffness is to the matrix.
double energy(const SparseSymmetric& K, const std::vector<double>& u) {
  std::vector<double> Ku(u.size());
  K.multiply(u.data(), Ku.data());
  double e = 0;
  for (std::size_t k = 0; k < u.size(); ++k) e += u[k] * Ku[k];
  return e;
}

// Keeping 20 of about 140 members drops most of each family's stiffness; the rescaling restores
// each row's second moment Σ h|ξ|², which sets the moduli of smooth fields. The kept bonds'
// directions sample the sphere unevenly and rows near a surface are rescaled by their own
// families, so the energies of stretching, shearing and bending are not exact: measured 0.955,
// 0.982 and 0.983 of the majoriser's on this bar, bound 8%. Without the rescaling they are
// 0.127, 0.120 and 0.167. (A rescaling off by a few percent passes here; the exact second moment
// above catches it: measured failing at 2%.)
TEST(NearestStiffness, LongWavesSeeTheFamilysStiffness) {
  const Scene scene = test::block_scene(
      {.size = {0.24, 0.06, 0.06}, .resolution = 0.012, .bulk = 3.3e10, .shear = 2.0e10});
  const Families& f = scene.families;
  const auto& x = scene.particles.reference;
  const auto [near, majoriser] = at_rest(scene, nearest_bonds(f, 20));
  const int n = scene.particles.count();
  struct Field {
    const char* label;
    std::vector<double> u;
  };
  std::vector<Field> fields = {{"stretch x", {}}, {"shear xy", {}}, {"bend xz", {}}};
  for (auto& field : fields) field.u.assign(3 * n, 0.0);
  for (int i = 0; i < n; ++i) {
    fields[0].u[3 * i] = x[3 * i];
    fields[1].u[3 * i] = x[3 * i + 1];
    fields[1].u[3 * i + 1] = x[3 * i];
    fields[2].u[3 * i + 2] = 0.5 * x[3 * i] * x[3 * i];
    fields[2].u[3 * i] = -x[3 * i] * (x[3 * i + 2] - 0.03);
  }
  double mean_family = 0;
  for (int i = 0; i < n; ++i) mean_family += f.offsets[i + 1] - f.offsets[i];
  std::printf("bar: %d particles, %.1f members per family on average\n", n, mean_family / n);
  for (const auto& field : fields) {
    const double ratio = energy(near, field.u) / energy(majoriser, field.u);
    std::printf("%s: u'K_near u / u'K_bw u = %.3f\n", field.label, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.08) << field.label;
  }
}

}  // namespace
}  // namespace fissure
