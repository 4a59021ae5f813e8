// The sparse grid (mpm/active_blocks.hpp, issue 17): exactly the blocks a point's stencil can
// reach are active, blocks no point reaches any more are released, mostly active grids take the
// dense pass; and a run in a box 100 times the body's volume is bitwise the run in its tight box
// (only active blocks are zeroed and updated, and the others are zero, as a dense pass leaves them).
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <set>
#include <string>

#include "deck/deck_reader.hpp"
#include "mpm/active_blocks.hpp"
#include "mpm/mpm_solver.hpp"
#include "run/simulation.hpp"

namespace test_active_blocks {

using namespace ballista;

namespace {

GridGeometry grid(int nx, int ny, int nz, int dim) {
  GridGeometry g;
  g.h = 1.0;
  g.nodes[0] = nx;
  g.nodes[1] = ny;
  g.nodes[2] = nz;
  g.dim = dim;
  return g;
}

std::set<Index> active_nodes(const ActiveBlocks& b, Index offset = 0) {
  std::set<Index> s;
  // Collected serially: the callback may run on several threads.
  std::vector<std::uint8_t> hit(1 << 20, 0);
  b.for_each_node(offset, [&](Index i) { hit[static_cast<std::size_t>(i)] = 1; });
  for (std::size_t i = 0; i < hit.size(); ++i)
    if (hit[i]) s.insert(static_cast<Index>(i));
  return s;
}

}  // namespace

TEST(ActiveBlocks, MarksTheBlocksOfEachStencilAndReleasesTheOldOnes) {
  const GridGeometry g = grid(40, 40, 40, 3);  // 5 x 5 x 5 blocks of 8^3 nodes
  ActiveBlocks b;
  b.reset(g);
  // A point in cell (3, 3, 3) with reach 1 touches nodes 2..5: block (0, 0, 0) only.
  const Vec3 p1{{3.5, 3.5, 3.5}};
  b.mark(&p1, 1, 1);
  b.finish();
  EXPECT_EQ(b.active_blocks(), 1);
  EXPECT_FALSE(b.dense());
  std::set<Index> nodes = active_nodes(b);
  EXPECT_EQ(nodes.size(), 512u);
  EXPECT_TRUE(nodes.count(g.node_index(7, 7, 7)));
  EXPECT_FALSE(nodes.count(g.node_index(8, 0, 0)));
  // In cell (7, 3, 3) the same reach touches node 9 in x: blocks (0,0,0) and (1,0,0).
  const Vec3 p2{{7.5, 3.5, 3.5}};
  b.mark(&p2, 1, 1);
  b.finish();
  EXPECT_EQ(b.active_blocks(), 2);
  // Moved to block (3, 3, 3): both earlier blocks are released, and only they.
  const Vec3 p3{{28.5, 28.5, 28.5}};
  b.mark(&p3, 1, 1);
  b.finish();
  EXPECT_EQ(b.active_blocks(), 1);
  std::set<Index> released;
  std::vector<std::uint8_t> hit(g.node_count(), 0);
  b.for_each_released_node(0, [&](Index i) { hit[static_cast<std::size_t>(i)] = 1; });
  for (Index i = 0; i < g.node_count(); ++i)
    if (hit[static_cast<std::size_t>(i)]) released.insert(i);
  EXPECT_EQ(released.size(), 1024u);
  EXPECT_TRUE(released.count(g.node_index(0, 0, 0)));
  EXPECT_TRUE(released.count(g.node_index(15, 7, 7)));
  // A second field's nodes are offset by the node count.
  EXPECT_TRUE(active_nodes(b, g.node_count()).count(g.node_count() + g.node_index(24, 24, 24)));
}

TEST(ActiveBlocks, PartialBlocksAtTheEdgeAnd2D) {
  const GridGeometry g = grid(10, 12, 1, 2);  // blocks of 8 x 8: 2 x 2, the last ones partial
  ActiveBlocks b;
  b.reset(g);
  const Vec3 p{{9.5, 11.5, 0.0}};  // outside the last cell: clamped to it
  b.mark(&p, 1, 0);
  b.finish();
  const std::set<Index> nodes = active_nodes(b);
  EXPECT_EQ(nodes.size(), 2u * 4u);  // nodes 8..9 by 8..11
  EXPECT_TRUE(nodes.count(g.node_index(9, 11, 0)));
  // Most of the grid active: the dense pass visits every node once.
  std::vector<Vec3> all;
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 10; ++i) all.push_back(Vec3{{i + 0.5, j + 0.5, 0.0}});
  b.mark(all.data(), static_cast<Index>(all.size()), 0);
  b.finish();
  EXPECT_TRUE(b.dense());
  EXPECT_EQ(active_nodes(b).size(), 120u);
}

TEST(ActiveBlocks, AHugeBoxGivesBitwiseTheTightBoxRun) {
  // A 3D J2 block thrown at a wall with GIMP and MUSL: once in a box 4 cells wider than it, once
  // in one ~100 times its volume with the same lower corner (the same nodes under the block).
  auto deck = [](double upper) {
    return "simulation: {dimension: 3d, end_time: 1.0, cfl: 0.3}\n"
           "mpm: {shape_function: gimp, update: musl}\n"
           "grid: {lower: [0, 0, 0], upper: [" +
           std::to_string(upper) + ", " + std::to_string(upper) + ", " + std::to_string(upper) +
           "], cell_size: 0.001, boundary: {y_min: wall}}\n"
           "materials:\n"
           "  steel: {model: j2_plasticity, density: 7850, youngs_modulus: 2.0e11, poisson_ratio: 0.29, "
           "yield_stress: 3.5e8, hardening_modulus: 1.0e9}\n"
           "bodies:\n"
           "  - {name: b, material: steel, velocity: [30, -200, 10], particles_per_cell: 2,\n"
           "     shape: {type: box, lower: [0.004, 0.0, 0.004], upper: [0.012, 0.006, 0.012]}}\n";
  };
  const Scenario tight = parse_deck(deck(0.016), "tight.yaml"), huge = parse_deck(deck(0.075), "huge.yaml");
  MpmSolver a(tight, make_materials(tight)), b(huge, make_materials(huge));
  for (int k = 0; k < 60; ++k) {
    const double dt = a.stable_dt();
    ASSERT_EQ(dt, b.stable_dt()) << "step " << k;
    a.step(dt);
    b.step(dt);
  }
  for (const char* f : {"x", "v", "F", "stress", "internal_energy"}) {
    const FieldStore& pa = a.points();
    const FieldStore& pb = b.points();
    ASSERT_EQ(pa.size(), pb.size());
    const std::size_t bytes = static_cast<std::size_t>(pa.size() * pa.info(f).ncomp) * sizeof(double);
    EXPECT_EQ(std::memcmp(pa.real(f), pb.real(f), bytes), 0) << f;
  }
  // No stale mass anywhere in the huge grid: its nodal mass sums to the tight grid's (round-off of
  // the two summation orders, 1e-12).
  double far_mass = 0.0;
  for (double m : b.grid().mass) far_mass += m;
  double total = 0.0;
  for (double m : a.grid().mass) total += m;
  EXPECT_NEAR(far_mass, total, 1e-12 * total);
}

TEST(ActiveBlocks, MirrorImagesOfBlocksNearAMirrorFace) {
  // Several ranks (mpm/grid_exchange.hpp): a rank holding a ghost node beyond a mirror face must
  // hold its image inside, and the other way round. Face at node 10 on x, band 3: a block whose
  // nodes reach 7..13 pulls in the blocks holding the reflected nodes; blocks farther away do not.
  const GridGeometry g = grid(32, 16, 1, 2);  // 4 x 2 blocks of 8 x 8
  ActiveBlocks b;
  b.reset(g);
  // A point in cell (12, 3) with reach 0: nodes 12..13, block (1, 0): within the band (10 +- 3).
  const Vec3 p{{12.5, 3.5, 0.0}};
  b.mark(&p, 1, 0);
  b.mark_mirror_images(0, 10, 3);
  b.finish();
  // Block (1, 0) covers nodes 8..15; its band part 8..13 reflects to 7..12: blocks (0,0), (1,0).
  const std::vector<Index>& active = b.active_list();
  ASSERT_EQ(active.size(), 2u);
  EXPECT_EQ(active[0], b.block_of(0, 0, 0));
  EXPECT_EQ(active[1], b.block_of(8, 0, 0));
  // A block beyond the band (nodes 24..31) pulls nothing in.
  const Vec3 far{{28.5, 3.5, 0.0}};
  b.mark(&far, 1, 0);
  b.mark_mirror_images(0, 10, 3);
  b.finish();
  ASSERT_EQ(b.active_list().size(), 1u);
  EXPECT_EQ(b.active_list()[0], b.block_of(24, 0, 0));
}

}  // namespace test_active_blocks
