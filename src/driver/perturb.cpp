#include "driver/perturb.hpp"

#include <random>
#include <sstream>

#include "core/error.hpp"

namespace ballista {

std::vector<FTableRow> perturb_table(std::vector<FTableRow> rows, double scale, double noise, std::uint64_t seed) {
  auto check = [&](size_t k, const char* what) {
    if (!(det(rows[k].F) > 0.0)) {
      std::ostringstream os;
      os << what << " makes det F = " << det(rows[k].F) << " <= 0 in F-table row " << k << " (t = " << rows[k].t
         << "); use a smaller value";
      throw Error(os.str());
    }
  };
  if (scale != 1.0)
    for (size_t k = 0; k < rows.size(); ++k) {
      rows[k].F = Mat3::identity() + scale * (rows[k].F - Mat3::identity());
      check(k, "scale");
    }
  if (noise != 0.0 && rows.size() > 1) {
    std::mt19937_64 rng(seed);    // the engine's output sequence is fixed by the standard
    Mat3 F_prev_old = rows[0].F;  // unperturbed F_{k-1}
    for (size_t k = 1; k < rows.size(); ++k) {
      const Mat3 F_old = rows[k].F;
      const Mat3 G = F_old * inverse(F_prev_old);
      Mat3 Gp = Mat3::identity();
      for (int e = 0; e < 9; ++e) {
        // xi uniform in [-1, 1] from the top 53 bits (not std::uniform_real_distribution, whose
        // algorithm is implementation-defined).
        const double xi = static_cast<double>(rng() >> 11) * 0x1.0p-53 * 2.0 - 1.0;
        Gp.a[e] += (G.a[e] - Mat3::identity().a[e]) * (1.0 + noise * xi);
      }
      rows[k].F = Gp * rows[k - 1].F;
      F_prev_old = F_old;
      check(k, "noise");
    }
  }
  return rows;
}

}  // namespace ballista
