// The graded grid's axes (geometry/grid_axes.hpp): zones of exact cells, gaps graded within the
// ratio, the coarse cells where nothing is refined, and the errors for gradings that would
// violate their own limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "geometry/grid_axes.hpp"

namespace test_grid_axes {

using namespace ballista;

namespace {

GridSpec grid(double h, double grading = 1.2) {
  GridSpec g;
  g.lower = Vec3{{0.0, -0.01, 0.0}};
  g.upper = Vec3{{0.04, 0.15, 0.0}};
  g.cell_size = h;
  g.grading = grading;
  return g;
}

RefineZone zone(int axis, double from, double to, double h, const std::string& key = "grid.refine.0") {
  RefineZone z;
  z.axis = axis;
  z.from = from;
  z.to = to;
  z.cell_size = h;
  z.mark.key_path = key;
  return z;
}

/// Every neighbouring ratio within q, every cell within [hmin, hmax], nodes increasing from lo to hi.
void expect_graded(const std::vector<double>& n, double lo, double hi, double q, double hmin, double hmax) {
  ASSERT_GE(n.size(), 2u);
  EXPECT_DOUBLE_EQ(n.front(), lo);
  EXPECT_NEAR(n.back(), hi, 1e-15);
  for (std::size_t k = 0; k + 1 < n.size(); ++k) {
    const double h = n[k + 1] - n[k];
    EXPECT_GT(h, hmin * (1.0 - 1e-9)) << k;
    EXPECT_LT(h, hmax * (1.0 + 1e-9)) << k;
    if (k + 2 < n.size()) {
      const double r = (n[k + 2] - n[k + 1]) / h;
      EXPECT_LE(std::max(r, 1.0 / r), q * (1.0 + 1e-9)) << "cells " << k << ", " << k + 1;
    }
  }
}

std::string error_of(const GridSpec& g, int dim) {
  try {
    build_grid_axes(g, dim);
  } catch (const DeckError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(GridAxes, AUniformGridHasWholeCellsFromLowerAsTheMpmLayout) {
  GridSpec g = grid(1.0e-3);
  g.upper[0] = 0.0405;  // not a whole number of cells: the last node moves out to 0.041
  const GridAxes a = build_grid_axes(g, 2);
  ASSERT_EQ(a.cells(0), 41);
  EXPECT_EQ(a.node[0][41], 0.0 + 41 * 1.0e-3);
  EXPECT_EQ(a.cells(1), 160);
  EXPECT_EQ(a.node[2].size(), 1u);
}

TEST(GridAxes, AZoneHasItsCellsAndTheGapsAreGradedWithinTheRatio) {
  GridSpec g = grid(1.0e-3);
  g.refine = {zone(0, 0.0, 4.0e-3, 0.25e-3), zone(1, 20.0e-3, 135.0e-3, 0.5e-3)};
  const GridAxes a = build_grid_axes(g, 2);
  // The radial zone from the axis: 16 cells of 0.25 mm, then graded to 1 mm.
  for (int k = 0; k < 16; ++k) EXPECT_NEAR(a.node[0][k + 1] - a.node[0][k], 0.25e-3, 1e-15);
  EXPECT_EQ(a.node[0][16], 4.0e-3);
  expect_graded(a.node[0], 0.0, 0.04, 1.2, 0.25e-3, 1.0e-3);
  // The axial zone is exact at both ends, graded on either side.
  expect_graded(a.node[1], -0.01, 0.15, 1.2, 0.5e-3, 1.0e-3);
  EXPECT_NE(std::find(a.node[1].begin(), a.node[1].end(), 20.0e-3), a.node[1].end());
  EXPECT_NE(std::find(a.node[1].begin(), a.node[1].end(), 135.0e-3), a.node[1].end());
  EXPECT_DOUBLE_EQ(a.smallest(0), 0.25e-3);
  // Far from the zone the cells are nearly the coarse ones (blended to fill the gap exactly).
  EXPECT_LE(a.largest(0), 1.0e-3 * (1.0 + 1e-12));
  EXPECT_GT(a.largest(0), 0.97e-3);
  // Far fewer cells than the zone's size everywhere: 16 + a ramp + ~30 against 160.
  EXPECT_LT(a.cells(0), 60);
}

TEST(GridAxes, TheCellHoldingACoordinateGivesItsSize) {
  GridSpec g = grid(1.0e-3);
  g.refine = {zone(0, 0.0, 4.0e-3, 0.25e-3)};
  const GridAxes a = build_grid_axes(g, 2);
  EXPECT_NEAR(a.cell_size_at(0, 0.1e-3), 0.25e-3, 1e-15);   // inside the zone
  EXPECT_NEAR(a.cell_size_at(0, 3.99e-3), 0.25e-3, 1e-15);
  const auto& n = a.node[0];
  const double last = n[n.size() - 1] - n[n.size() - 2];
  EXPECT_EQ(a.cell_size_at(0, 0.5 * (n[n.size() - 2] + n.back())), last);  // the outermost cell
  EXPECT_EQ(a.cell_size_at(0, 1.0), last);                                  // beyond the box: the end cell's
  EXPECT_NEAR(a.cell_size_at(0, -1.0), 0.25e-3, 1e-15);
  EXPECT_NEAR(a.cell_size_at(1, 0.07), 1.0e-3, 1e-15);                      // an axis without zones
}

TEST(GridAxes, AZoneNotAWholeNumberOfItsCellsGetsSlightlySmallerOnes) {
  GridSpec g = grid(1.0e-3);
  g.refine = {zone(0, 0.0, 3.9e-3, 0.25e-3)};
  const GridAxes a = build_grid_axes(g, 2);
  EXPECT_NEAR(a.node[0][1], 3.9e-3 / 16, 1e-15);  // 16 cells of 0.24375 mm
  EXPECT_EQ(a.node[0][16], 3.9e-3);
}

TEST(GridAxes, GradingsThatWouldViolateTheirLimitsAreDeckErrors) {
  GridSpec g = grid(1.0e-3);
  g.refine = {zone(0, 0.0, 5.0e-3, 0.25e-3), zone(0, 4.0e-3, 8.0e-3, 0.5e-3, "grid.refine.1")};
  EXPECT_NE(error_of(g, 2).find("overlaps another zone"), std::string::npos) << error_of(g, 2);
  g.refine = {zone(0, 0.0, 4.0e-3, 0.25e-3), zone(0, 4.0e-3, 8.0e-3, 0.5e-3, "grid.refine.1")};
  EXPECT_NE(error_of(g, 2).find("meet at x = 0.004 m: a ratio of 2"), std::string::npos) << error_of(g, 2);
  g.refine = {zone(0, 0.0, 4.0e-3, 0.1e-3), zone(0, 4.3e-3, 8.0e-3, 0.5e-3, "grid.refine.1")};
  EXPECT_NE(error_of(g, 2).find("too short to grade"), std::string::npos) << error_of(g, 2);
  g.refine = {zone(0, 0.0, 4.0e-3, 2.0e-3)};
  EXPECT_NE(error_of(g, 2).find("finer than grid.cell_size"), std::string::npos) << error_of(g, 2);
  g.refine = {zone(1, 0.0, 0.2, 0.5e-3)};
  EXPECT_NE(error_of(g, 2).find("outside the grid's y range"), std::string::npos) << error_of(g, 2);
  EXPECT_NE(error_of(g, 2).find("grid.refine.0"), std::string::npos);
  // A gap of 0.45 mm from 0.1 to 0.5 mm cells: impossible within 1.2 (the ramp alone needs 1.5
  // mm), two cells (0.2 and 0.25 mm) within 2.
  g.refine = {zone(0, 0.0, 4.0e-3, 0.1e-3), zone(0, 4.45e-3, 8.0e-3, 0.5e-3, "grid.refine.1")};
  EXPECT_NE(error_of(g, 2).find("too short to grade"), std::string::npos);
  g.grading = 2.0;
  EXPECT_EQ(error_of(g, 2), "");
  const GridAxes a = build_grid_axes(g, 2);
  expect_graded(a.node[0], 0.0, 0.04, 2.0, 0.1e-3, 1.0e-3);
}

}  // namespace test_grid_axes
