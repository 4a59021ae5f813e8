// Writes an Exodus II tetrahedral mesh of a solid cylinder for the LGR OTM Taylor-bar benchmark
// (bench/peers/lgr_otm_taylor.sh). Project code, not LGR code; needs only the Debian exodusII
// library (libexodusii-dev).
//
//   lgr_cylinder_exo OUT.g RADIUS LENGTH N_ACROSS N_AXIAL
//
// The bar occupies z in [-LENGTH, 0] (LGR's OTM Taylor setup has its rigid wall at z = 0 and the
// bar moving in +z). The cross-section is an N_ACROSS x N_ACROSS square grid mapped onto the disk
// (elliptical square-to-disk map); each hexahedron is cut into 6 tetrahedra (Kuhn subdivision,
// conforming), so tets = 6 * N_ACROSS^2 * N_AXIAL, nodes = (N_ACROSS+1)^2 * (N_AXIAL+1).
#include <exodusII.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

int main(int argc, char** argv)
{
  if (argc != 6) {
    std::fprintf(stderr, "usage: %s OUT.g RADIUS LENGTH N_ACROSS N_AXIAL\n", argv[0]);
    return 2;
  }
  const char*  out = argv[1];
  const double R   = std::atof(argv[2]);
  const double L   = std::atof(argv[3]);
  const int    n   = std::atoi(argv[4]);
  const int    nz  = std::atoi(argv[5]);
  if (n < 1 || nz < 1 || R <= 0 || L <= 0) return 2;

  auto node_id = [&](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  const int           nn = (n + 1) * (n + 1) * (nz + 1);
  std::vector<double> x(nn), y(nn), z(nn);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double u = -1.0 + 2.0 * i / n, v = -1.0 + 2.0 * j / n;
        const int    id = node_id(i, j, k);
        x[id] = R * u * std::sqrt(1.0 - 0.5 * v * v);
        y[id] = R * v * std::sqrt(1.0 - 0.5 * u * u);
        z[id] = -L + L * double(k) / nz;
      }

  // Kuhn subdivision: each tet follows a monotone path from corner (0,0,0) to (1,1,1).
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::vector<int> conn;
  conn.reserve(size_t(6) * n * n * nz * 4);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (auto const& p : perms) {
          int c[3] = {0, 0, 0};
          int t[4];
          t[0] = node_id(i, j, k);
          for (int s = 0; s < 3; ++s) {
            c[p[s]] = 1;
            t[s + 1] = node_id(i + c[0], j + c[1], k + c[2]);
          }
          // make the signed volume positive
          const double ax = x[t[1]] - x[t[0]], ay = y[t[1]] - y[t[0]], az = z[t[1]] - z[t[0]];
          const double bx = x[t[2]] - x[t[0]], by = y[t[2]] - y[t[0]], bz = z[t[2]] - z[t[0]];
          const double cx = x[t[3]] - x[t[0]], cy = y[t[3]] - y[t[0]], cz = z[t[3]] - z[t[0]];
          const double vol = ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
          if (vol < 0) std::swap(t[2], t[3]);
          for (int s = 0; s < 4; ++s) conn.push_back(t[s] + 1);  // Exodus is 1-based
        }
  const int ne = int(conn.size() / 4);

  int cpu_ws = sizeof(double), io_ws = sizeof(double);
  int exo = ex_create(out, EX_CLOBBER, &cpu_ws, &io_ws);
  if (exo < 0) { std::fprintf(stderr, "ex_create failed\n"); return 1; }
  int err = 0;
  err |= ex_put_init(exo, "cylinder for LGR OTM Taylor benchmark", 3, nn, ne, 1, 0, 0);
  err |= ex_put_coord(exo, x.data(), y.data(), z.data());
  err |= ex_put_block(exo, EX_ELEM_BLOCK, 1, "TETRA4", ne, 4, 0, 0, 0);
  err |= ex_put_conn(exo, EX_ELEM_BLOCK, 1, conn.data(), nullptr, nullptr);
  err |= ex_close(exo);
  if (err) { std::fprintf(stderr, "exodus write error\n"); return 1; }
  std::printf("wrote %s: %d nodes, %d tets\n", out, nn, ne);
  return 0;
}
