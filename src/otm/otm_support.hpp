#pragma once
// Support domains of the OTM material points and their LME shape functions (seed 003 Fig. 2-1,
// eq. 2.12): for each point, the nodes of its own body within the support radius
// r_s = h sqrt(-ln(tol) / gamma) (beyond it a node's weight exp(-beta r^2) is below tol of the
// nearest node's: Arroyo & Ortiz 2006 §4 truncate the same way), found through a cell binning of
// the nodes (O(N)); then N_a and grad N_a at the point. A point with fewer than `min_support`
// nodes in reach counts as a failed solve (and is retried with its previous nodes, below).
//
// Rebuilt every step, from the current node and point positions: the seed recomputes supports
// every few steps (Fig. 2-1 caption), but Algorithm 1 line 7 evaluates the shape functions every
// step anyway. The binned search itself is not redone every step: each point keeps the nodes
// within a wider radius (a Verlet list, Verlet 1967), and while no point and node can have come
// within its radius from outside that margin, its support is picked from that list, the same
// nodes in the same order as a search would give (docs/performance.md).
#include <cstdint>
#include <vector>

#include "core/parallel.hpp"
#include "core/tensor.hpp"
#include "otm/lme_shape.hpp"

namespace ballista::otm {

struct SupportOptions {
  double h = 0.0;                ///< m, nodal spacing (beta = gamma / h^2)
  double gamma = 1.8;            ///< LME locality
  double tolerance = 1e-4;       ///< weight cut-off of the support radius
  int min_support = 0;           ///< fewest nodes per point (0: dim + 2)
  int dim = 3;
  LmeOptions lme;
};

/// Compressed rows: point p's nodes node[offset[p] .. offset[p+1]) with N and grad N (1/m).
struct Supports {
  std::vector<Index> offset;
  std::vector<std::int32_t> node;
  std::vector<double> N;
  std::vector<Vec3> dN;
  // Statistics of the last build.
  double mean_size = 0.0;
  int max_size = 0;
  int max_iterations = 0;
  double max_condition = 0.0;
  Index fallbacks = 0;              ///< points solved by the Levenberg-Marquardt fallback
  Index retries = 0;                ///< points solved again with their previous nodes added
  Index failed = -1;                ///< first point whose LME solve failed (-1: none)
  std::vector<Index> unsolved;      ///< every point whose solve failed, in increasing index
  LmeResult failed_result;          ///< its solve
  Index size() const { return static_cast<Index>(offset.size()) - 1; }
};

/// Candidate nodes of each point (Verlet lists): the nodes of its body within reach[p] = kSkin
/// times its support radius at the search, in increasing index, with the positions and bodies the
/// search saw.
struct SupportCandidates {
  std::vector<Index> offset;
  std::vector<std::int32_t> node;
  std::vector<double> reach;
  std::vector<Vec3> point_x, node_x;
  std::vector<std::int64_t> point_body, node_body;
  Index searches = 0;  ///< how many times the lists were searched
};

/// Margin of the candidate lists, as a factor on each point's support radius: wider lists cost
/// more to filter each step (the factor cubed in 3D) and are searched again less often.
inline constexpr double kSkin = 1.2;

/// Supports and shape functions of points xp[0..np) (bodies pbody) over nodes xn[0..nn) (bodies
/// nbody); lambda[p] is each point's LME multiplier (warm start in, solution out).
///
/// With `candidates` (may be null) each point's nodes are taken from its candidate list while
/// every point p satisfies r_p + |x_p - x_p'| + max_a |x_a - x_a'| <= reach_p (' at the lists'
/// search, bodies unchanged; so by the triangle inequality no node within r_p of it can be
/// missing), else the lists are searched again; the supports are the same either way.
///
/// scale[p] (>= 1, may be null) widens point p's radius: the nodes move with the material, so
/// where it has been stretched by s the nodes around a point are s times further apart (the solver
/// passes the largest principal stretch of F_p, capped at kMaxScale). `previous` (may be null) are
/// the supports of the last build: a point whose solve fails with its new nodes is solved again with
/// the union of its new and previous nodes. It was a convex combination of the previous ones
/// (x_p = sum N_a x_a, Algorithm 1 line 12), so it lies in their hull and the solve exists; the
/// retries are counted.
void build_supports(const Vec3* xp, const std::int64_t* pbody, Index np, const Vec3* xn, const std::int64_t* nbody,
                    Index nn, const SupportOptions& opt, const double* scale, const Supports* previous, Vec3* lambda,
                    Supports& out, SupportCandidates* candidates = nullptr);

/// Largest radius scale honoured by build_supports (the bins are sized for it).
inline constexpr double kMaxScale = 4.0;

/// Support radius for the options: h sqrt(-ln(tol) / gamma).
double support_radius(const SupportOptions& opt);

/// Influence domains (seed 003 Fig. 2-1): the transpose of the supports, node a's entries
/// entry[start[a] .. start[a+1]) index the support arrays (N, dN) and owner[] names their points,
/// in increasing point order. Node-wise gathers over it are deterministic for any thread count.
struct Influences {
  std::vector<Index> start, entry, owner;
};

/// The influence domains of `sup` over nn nodes (a counting sort: O(entries)).
void build_influences(const Supports& sup, Index nn, Influences& out);

}  // namespace ballista::otm
