#pragma once
// Perturbed replays of an F-table (thesis seed 000 §4.2.2: archived particle histories "perturbed
// ... to generate an infinite number of unique but similar histories" to probe a model's
// robustness near a failure).
#include <cstdint>
#include <vector>

#include "driver/point_driver.hpp"

namespace ballista {

/// Returns the table with
///  1. every F scaled about the identity: F -> I + scale (F - I) (scale 1: unchanged), then
///  2. multiplicative noise on the increments (noise 0: unchanged): with G_k = F_k F_{k-1}^{-1}
///     the deformation of row k, G'_k = I + (G_k - I) o (1 + noise xi_k) entrywise, xi_k
///     uniform in [-1, 1] (9 independent values per row from a 64-bit Mersenne twister seeded with
///     `seed`: the same seed gives the same table on every platform), and F'_k = G'_k F'_{k-1}.
/// Times and rotation columns are kept. Throws Error naming the row if a perturbed F has
/// det F <= 0 (noise or scale too large).
std::vector<FTableRow> perturb_table(std::vector<FTableRow> rows, double scale, double noise, std::uint64_t seed);

}  // namespace ballista
