// The MPM grid's face and axis conditions: symmetry faces folded and filled by mirror images (the
// cubic B-spline), and the velocity constraints of every face kind with the impulses they book.
#include <algorithm>

#include "mpm/mpm_solver.hpp"

namespace ballista {

namespace {
/// Calls f(ghost, image, axis) for every node on (ghost == image) and beyond a mirror face and its
/// mirror image (both as node indices of field 0), faces in the given order, every node of the
/// transverse planes (ghost layers included, so that corners between two mirror faces are folded
/// twice).
template <class Face, class Fn>
void for_each_mirror_pair(const GridGeometry& g, int ghost, const std::vector<Face>& faces, Fn&& fn) {
  for (const Face& mf : faces) {
    const int a = mf.axis, b1 = (a + 1) % 3, b2 = (a + 2) % 3;
    for (int k = 0; k <= ghost; ++k) {
      const int gi = mf.node + mf.side * k, ii = mf.node - mf.side * k;
      if (gi < 0 || gi >= g.nodes[a] || ii < 0 || ii >= g.nodes[a]) continue;
      for (int j = 0; j < g.nodes[b1]; ++j)
        for (int l = 0; l < g.nodes[b2]; ++l) {
          int G[3], I[3];
          G[a] = gi; I[a] = ii;
          G[b1] = I[b1] = j;
          G[b2] = I[b2] = l;
          fn(g.node_index(G[0], G[1], G[2]), g.node_index(I[0], I[1], I[2]), a);
        }
    }
  }
}
/// The mirror image of v across a plane normal to `axis`.
inline Vec3 mirrored(Vec3 v, int axis) {
  v[axis] = -v[axis];
  return v;
}
}  // namespace

void MpmSolver::fold_mirror_faces(P2gPart part) {
  // Image particles (the body reflected in the face) would add to inside node I what the real
  // ones put on its mirror ghost G, reflected: m_I += m_G, p_I += R p_G, f_I += R f_G (the image's
  // stress R sigma R and gradient R grad N_G give R f_G; the axisymmetric hoop term flips with r).
  // A face node is its own image: p += R p, f += R f cancel the normal components (and double
  // the tangential ones with the mass, which changes neither v nor a), so the mapped velocity of
  // the face nodes has no normal part either, as in the whole body; the acceleration handed to the
  // particles, (v_new - v)/dt, then has none there. Ghost nodes are left empty;
  // fill_mirror_ghosts sets them.
  const GridGeometry& g = grid_.geom;
  const Index nn = g.node_count();
  for (int f = 0; f < grid_.fields; ++f) {
    const Index o = f * nn;
    for_each_mirror_pair(g, ghost_, mirror_faces_, [&](Index G, Index I, int a) {
      G += o;
      I += o;
      // Only the sums this pass formed (the others were folded when they were formed).
      if (G == I) {
        if (maps_momentum(part)) grid_.velocity[I][a] = 0.0;
        if (maps_forces(part)) grid_.force[I][a] = 0.0;
        if (maps_mass(part) && grid_.fields > 1) grid_.grad[I][a] = 0.0;
        // The image fills the other half of the face node.
        if (maps_volume(part) && grid_.with_volume) grid_.volume[I] *= 2.0;
        return;
      }
      if (maps_momentum(part)) {
        grid_.velocity[I] += mirrored(grid_.velocity[G], a);
        grid_.velocity[G] = Vec3{};
      }
      if (maps_mass(part)) {
        grid_.mass[I] += grid_.mass[G];
        grid_.mass[G] = 0.0;
      }
      if (maps_forces(part)) {
        grid_.force[I] += mirrored(grid_.force[G], a);
        grid_.force[G] = Vec3{};
      }
      if (maps_mass(part) && grid_.fields > 1) {
        grid_.grad[I] += mirrored(grid_.grad[G], a);
        grid_.grad[G] = Vec3{};
      }
      if (maps_volume(part) && grid_.with_volume) {
        grid_.volume[I] += grid_.volume[G];
        grid_.volume[G] = 0.0;
      }
    });
  }
}

void MpmSolver::fill_mirror_ghosts(Vec3* v) {
  const GridGeometry& g = grid_.geom;
  const Index nn = g.node_count();
  for (int f = 0; f < grid_.fields; ++f) {
    Vec3* vf = v + f * nn;
    for_each_mirror_pair(g, ghost_, mirror_faces_, [&](Index G, Index I, int a) {
      if (G != I) vf[G] = mirrored(vf[I], a);
    });
  }
}

void MpmSolver::apply_velocity_bcs(Vec3* vel_all, std::vector<BoundaryImpulse>* impulses) {
  // Every field's nodes obey the face conditions. The faces are at rest, so in the continuum their
  // reactions do no work; on the grid the constraint stops the normal momentum a node carries into
  // the face (or onto the axis) within the step, an inelastic impulse m c. With `impulses` each
  // change c is recorded, and book_impulses books its work as the "boundary work" of the energy
  // audit.
  const GridGeometry& g = grid_.geom;
  const Index nn = g.node_count();
  // Sets component a of node I of field f to u_new, recording the change.
  auto constrain = [&](int f, Index I, int a, double u_new) {
    Vec3& u = vel_all[f * nn + I];
    if (impulses && u[a] != u_new) impulses->push_back({f * nn + I, a, u_new - u[a]});
    u[a] = u_new;
  };
  for (int f = 0; f < grid_.fields; ++f) {
    Vec3* vel = vel_all + f * nn;
    if (dimension_ == Dimension::Axisymmetric && layout_.box_lower[0] == 0.0) {
      // The symmetry axis: radial velocity is zero on it (and on the ghost nodes beyond it) whatever
      // the x_min condition says; without this the hoop rate v_r / r of the particles next to the
      // axis is unbounded.
      for (int i = 0; i <= layout_.box_first[0]; ++i)
        for (int j = 0; j < g.nodes[1]; ++j) constrain(f, g.node_index(i, j, 0), 0, 0.0);
    }
    for (int a = 0; a < dim_; ++a) {
      for (int side = 0; side < 2; ++side) {
        const FaceBC bc = scenario_.grid.faces[2 * a + side];
        if (bc == FaceBC::Free) continue;
        // Nodes on the face and the ghost layers beyond it.
        const int lo = side == 0 ? 0 : layout_.box_last[a];
        const int hi = side == 0 ? layout_.box_first[a] : g.nodes[a] - 1;
        const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;
        for (int i = lo; i <= hi; ++i)
          for (int j = 0; j < g.nodes[b1]; ++j)
            for (int k = 0; k < g.nodes[b2]; ++k) {
              int ijk[3];
              ijk[a] = i; ijk[b1] = j; ijk[b2] = k;
              const Index I = g.node_index(ijk[0], ijk[1], ijk[2]);
              const Vec3& u = vel[I];
              switch (bc) {
                case FaceBC::Fixed:
                  for (int c = 0; c < 3; ++c) constrain(f, I, c, 0.0);
                  break;
                case FaceBC::Symmetry: constrain(f, I, a, 0.0); break;
                case FaceBC::Wall:  // rigid frictionless wall: no velocity into the wall, separation allowed
                  constrain(f, I, a, side == 0 ? std::max(u[a], 0.0) : std::min(u[a], 0.0));
                  break;
                case FaceBC::Free: break;
              }
            }
      }
    }
  }
}

}  // namespace ballista
