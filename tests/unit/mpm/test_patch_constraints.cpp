// The hanging nodes of a grid with patches (mpm/patch_constraints.hpp): the basis that remains
// after folding the hanging nodes into their masters is, at each point, the bilinear hat of the
// cells of the region it lies in (the grid's own cells outside every patch, a patch's own cells in
// it, a nested patch's in that), keeps the partition of unity and reproduces linear fields
// everywhere, and filling interpolates a linear field exactly. Bounds: identities exact in real
// arithmetic against 1e-12 (a few dozen rounded terms of size <= the box's extent, 2 m); the
// patch's deck errors name the patch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "core/error.hpp"
#include "geometry/grid_axes.hpp"
#include "mpm/patch_constraints.hpp"

namespace test_patch_constraints {

using namespace ballista;

namespace {

constexpr int kGhost = 3;

/// A 2 m square of 0.25 m cells with one patch of `h` cells over [0.5, 1.0] x [0.75, 1.25].
GridSpec spec(double h = 0.0625) {
  GridSpec g;
  g.lower = Vec3{{0.0, 0.0, 0.0}};
  g.upper = Vec3{{2.0, 2.0, 0.0}};
  g.cell_size = 0.25;
  GridPatch p;
  p.lower = Vec3{{0.5, 0.75, 0.0}};
  p.upper = Vec3{{1.0, 1.25, 0.0}};
  p.cell_size = h;
  p.mark.key_path = "grid.patches.0";
  g.patches.push_back(p);
  return g;
}

/// The grid as the MPM solver lays it out: each axis continued by kGhost end cells each side.
GridGeometry geometry(const GridAxes& axes) {
  GridGeometry g;
  g.dim = 2;
  auto graded = std::make_shared<std::array<GradedAxis, 3>>();
  for (int a = 0; a < 3; ++a) {
    if (a >= 2) {
      g.nodes[a] = 1;
      continue;
    }
    const std::vector<double>& box = axes.node[a];
    std::vector<double> n;
    for (int k = kGhost; k > 0; --k) n.push_back(box.front() - k * (box[1] - box[0]));
    n.insert(n.end(), box.begin(), box.end());
    for (int k = 1; k <= kGhost; ++k)
      n.push_back(box.back() + k * (box.back() - box[box.size() - 2]));
    (*graded)[a] = GradedAxis(n);
    g.nodes[a] = static_cast<int>(n.size());
    g.origin[a] = n.front();
  }
  g.graded = graded;
  g.h = 0.0625;
  return g;
}

/// The bilinear hat weights of the tensor grid at x, as a node array.
std::vector<double> tensor_weights(const GridGeometry& g, const Vec3& x) {
  std::vector<double> w(static_cast<std::size_t>(g.node_count()), 0.0);
  int c[2];
  double t[2];
  for (int a = 0; a < 2; ++a) (*g.graded)[a].locate(x[a], c[a], t[a]);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      w[static_cast<std::size_t>(g.node_index(c[0] + i, c[1] + j, 0))] =
          (i ? t[0] : 1.0 - t[0]) * (j ? t[1] : 1.0 - t[1]);
  return w;
}

/// A 2 m square of 0.25 m cells with a patch of 0.125 m cells over [0.5, 1.25]^2 and one of
/// 0.0625 m cells nested in it over [0.75, 1.0]^2.
GridSpec nested_spec() {
  GridSpec g = spec(0.125);
  g.patches[0].lower = Vec3{{0.5, 0.5, 0.0}};
  g.patches[0].upper = Vec3{{1.25, 1.25, 0.0}};
  GridPatch q;
  q.lower = Vec3{{0.75, 0.75, 0.0}};
  q.upper = Vec3{{1.0, 1.0, 0.0}};
  q.cell_size = 0.0625;
  q.mark.key_path = "grid.patches.1";
  g.patches.push_back(q);
  return g;
}

/// The bilinear hat at node (xn, yn) of the cell holding x of the region x lies in (the deepest
/// patch holding it, or the grid's own cells).
double region_hat(const GridAxes& axes, const Vec3& x, double xn, double yn) {
  double w = 1.0;
  const double at[2] = {xn, yn};
  const int region = axes.innermost_holding(x, 2);
  for (int a = 0; a < 2; ++a) {
    const std::vector<double>& n = axes.lattice_of(region, a);
    const auto hi = std::upper_bound(n.begin(), n.end(), x[a]);
    const double x0 = *(hi - 1), x1 = *hi;
    if (std::abs(at[a] - x0) < 1e-12)
      w *= (x1 - x[a]) / (x1 - x0);
    else if (std::abs(at[a] - x1) < 1e-12)
      w *= (x[a] - x0) / (x1 - x0);
    else
      return 0.0;
  }
  return w;
}

/// Every hanging node's masters are free and its weights sum to one; returns which nodes hang.
std::vector<char> expect_free_masters_weighing_one(const PatchConstraints& pc, const GridGeometry& g) {
  std::vector<char> hanging(static_cast<std::size_t>(g.node_count()), 0);
  for (const auto& h : pc.hanging()) hanging[static_cast<std::size_t>(h.node)] = 1;
  for (const auto& h : pc.hanging()) {
    double sum = 0.0;
    for (int m = 0; m < h.count; ++m) {
      EXPECT_FALSE(hanging[static_cast<std::size_t>(pc.master(h, m))]) << "node " << h.node;
      sum += pc.weight(h, m);
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << "node " << h.node;
  }
  return hanging;
}

}  // namespace

TEST(PatchConstraints, MastersAreFreeNodesOfTheCoarseCellAndWeightsSumToOne) {
  const GridAxes axes = build_grid_axes(spec(), 2);
  const GridGeometry g = geometry(axes);
  const PatchConstraints pc(g, axes, kGhost);
  ASSERT_FALSE(pc.empty());
  EXPECT_EQ(pc.reach(), 4);  // 0.25 / 0.0625: a hanging node's masters span 4 of the grid's cells
  const std::vector<char> hanging = expect_free_masters_weighing_one(pc, g);
  // Inside the patch (strictly) no node hangs: its split cells are whole.
  const Vec3 mid{{0.75, 1.0, 0.0}};
  int ci, cj;
  double t;
  (*g.graded)[0].locate(mid[0], ci, t);
  (*g.graded)[1].locate(mid[1], cj, t);
  EXPECT_FALSE(hanging[static_cast<std::size_t>(g.node_index(ci, cj, 0))]);
}

/// Whether the cell of x's region holding x has no corner on the region's faces (whose nodes off
/// the parent's lattice hang, so that the basis there is the parent's along the face).
bool cell_clear_of_faces(const GridAxes& axes, const Vec3& x) {
  const int region = axes.innermost_holding(x, 2);
  if (region < 0) return true;
  const PatchBox& b = axes.patches[static_cast<std::size_t>(region)];
  for (int a = 0; a < 2; ++a) {
    const std::vector<double>& n = b.lattice[a];
    const auto hi = std::upper_bound(n.begin(), n.end(), x[a]);
    if (*(hi - 1) == b.lower[a] || *hi == b.upper[a]) return false;
  }
  return true;
}

/// Folds the tensor grid's weights at random points of [0.3, 1.7]^2 and checks them against the
/// region's hat away from its faces, and the partition of unity and linear reproduction
/// everywhere; returns how many points fell in each region (-1: the grid's own cells) in cells
/// clear of its faces.
std::vector<int> check_folded_basis(const GridSpec& spec_in) {
  const GridAxes axes = build_grid_axes(spec_in, 2);
  const GridGeometry g = geometry(axes);
  const PatchConstraints pc(g, axes, kGhost);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.3, 1.7), near_x(0.45, 1.3), near_y(0.45, 1.3);
  std::vector<int> count(axes.patches.size() + 1, 0);
  for (int trial = 0; trial < 2000; ++trial) {
    // Half the points around the patches, where the regions meet.
    const Vec3 x = trial % 2 ? Vec3{{u(rng), u(rng), 0.0}} : Vec3{{near_x(rng), near_y(rng), 0.0}};
    std::vector<double> w = tensor_weights(g, x);
    pc.fold(w.data(), g.node_count(), 1);
    double sum = 0.0, sx = 0.0, sy = 0.0;
    const bool own_hat = cell_clear_of_faces(axes, x);
    for (Index I = 0; I < g.node_count(); ++I) {
      const Vec3 xn =
          g.node_position(static_cast<int>(I % g.nodes[0]), static_cast<int>(I / g.nodes[0]), 0);
      sum += w[static_cast<std::size_t>(I)];
      sx += w[static_cast<std::size_t>(I)] * xn[0];
      sy += w[static_cast<std::size_t>(I)] * xn[1];
      if (own_hat)
        EXPECT_NEAR(w[static_cast<std::size_t>(I)], region_hat(axes, x, xn[0], xn[1]), 1e-12)
            << "point " << x[0] << ", " << x[1] << " node " << xn[0] << ", " << xn[1];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << x[0] << ", " << x[1];
    EXPECT_NEAR(sx, x[0], 1e-12) << x[0] << ", " << x[1];
    EXPECT_NEAR(sy, x[1], 1e-12) << x[0] << ", " << x[1];
    if (own_hat) ++count[static_cast<std::size_t>(axes.innermost_holding(x, 2) + 1)];
  }
  return count;
}

TEST(PatchConstraints, TheFoldedBasisIsTheRegionsHatAndCompleteEverywhere) {
  const std::vector<int> count = check_folded_basis(spec());
  EXPECT_GT(count[0], 300);  // outside the patch: the coarse cell's hat
  EXPECT_GT(count[1], 100);  // inside it: the split cells'
}

TEST(PatchConstraints, NestedPatchesFoldToEachRegionsHat) {
  const std::vector<int> count = check_folded_basis(nested_spec());
  EXPECT_GT(count[0], 300);  // the grid's own cells
  EXPECT_GT(count[1], 100);  // the outer patch's 0.125 m cells, beside the inner patch's lines
  EXPECT_GT(count[2], 20);   // the inner patch's 0.0625 m cells (2 x 2 of them clear of its faces)
}

TEST(PatchConstraints, NestedPatchesHangOnFreeMasters) {
  const GridAxes axes = build_grid_axes(nested_spec(), 2);
  const GridGeometry g = geometry(axes);
  const PatchConstraints pc(g, axes, kGhost);
  // A node of the inner patch's lines outside the outer patch hangs on the 0.25 m cell's corners,
  // which span four of the grid's cells (each 0.125 m split split again).
  EXPECT_EQ(pc.reach(), 4);
  expect_free_masters_weighing_one(pc, g);
}

class Filling : public ::testing::TestWithParam<bool> {};

TEST_P(Filling, InterpolatesALinearFieldExactly) {
  const GridAxes axes = build_grid_axes(GetParam() ? nested_spec() : spec(), 2);
  const GridGeometry g = geometry(axes);
  const PatchConstraints pc(g, axes, kGhost);
  std::vector<Vec3> v(static_cast<std::size_t>(2 * g.node_count()));
  auto field = [](const Vec3& x, int f) {
    return Vec3{{1.0 + 2.0 * x[0] - 3.0 * x[1] + f, 0.5 * x[0] + x[1], 0.0}};
  };
  for (int f = 0; f < 2; ++f)
    for (Index I = 0; I < g.node_count(); ++I)
      v[static_cast<std::size_t>(f * g.node_count() + I)] = field(
          g.node_position(static_cast<int>(I % g.nodes[0]), static_cast<int>(I / g.nodes[0]), 0),
          f);
  std::vector<Vec3> before = v;
  for (const auto& h : pc.hanging())  // spoil the hanging nodes of both fields
    for (int f = 0; f < 2; ++f)
      v[static_cast<std::size_t>(f * g.node_count() + h.node)] = Vec3{{9.0, 9.0, 9.0}};
  pc.fill(v.data(), g.node_count(), 2);
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[i][c], before[i][c], 1e-12) << i;
}

INSTANTIATE_TEST_SUITE_P(PatchConstraints, Filling, ::testing::Bool());

TEST(PatchConstraints, DeckErrorsNameThePatch) {
  auto expect_error = [](GridSpec g, const std::string& key, const std::string& words) {
    try {
      build_grid_axes(g, 2);
      ADD_FAILURE() << "no error for " << words;
    } catch (const DeckError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  GridSpec off = spec();
  off.patches[0].lower[0] = 0.6;
  expect_error(off, "grid.patches.0.lower", "is not a node of the grid");
  GridSpec outside = spec();
  outside.patches[0].upper[1] = 2.5;
  expect_error(outside, "grid.patches.0.upper", "lies outside the grid");
  GridSpec coarse = spec(0.25);
  expect_error(coarse, "grid.patches.0.cell_size", "expected cells finer");
  GridSpec two = spec();
  GridPatch q = two.patches[0];
  q.lower = Vec3{{0.75, 1.0, 0.0}};
  q.upper = Vec3{{1.5, 1.5, 0.0}};
  q.mark.key_path = "grid.patches.1";
  two.patches.push_back(q);
  expect_error(two, "grid.patches.1", "without lying inside it");
  GridSpec other = spec();
  q = other.patches[0];
  q.lower = Vec3{{0.75, 1.5, 0.0}};
  q.upper = Vec3{{1.5, 1.75, 0.0}};
  q.cell_size = 0.125;
  q.mark.key_path = "grid.patches.1";
  other.patches.push_back(q);
  expect_error(other, "grid.patches.1.cell_size", "split it alike");
  GridSpec off_parent = nested_spec();  // on the grid's 0.0625 m lines but not the outer patch's
  off_parent.patches[1].lower[0] = 0.6875;
  expect_error(off_parent, "grid.patches.1.lower",
               "is not a node of the patch it lies in (grid.patches.0)");
  GridSpec not_finer = nested_spec();
  not_finer.patches[1].cell_size = 0.125;
  expect_error(not_finer, "grid.patches.1.cell_size",
               "expected cells finer than the 0.125 m cells");
  GridSpec touching = nested_spec();  // the inner patch on the outer's face x = 0.5 m
  touching.patches[1].lower[0] = 0.5;
  expect_error(touching, "grid.patches.1.lower",
               "is a face of the patch it lies in (grid.patches.0)");
  GridSpec same = nested_spec();
  same.patches[1].lower = same.patches[0].lower;
  same.patches[1].upper = same.patches[0].upper;
  expect_error(same, "grid.patches.0", "the same box as grid.patches.1");
}

}  // namespace test_patch_constraints
