// The MPM grid between the mappings: contact, the grid update with damping and the face
// conditions, and the work of the impulses they make.
#include "core/parallel.hpp"
#include "mpm/grid_contact.hpp"
#include "mpm/mpm_solver.hpp"

namespace ballista {

void MpmSolver::apply_contact(Vec3* vel, bool book) {
  if (grid_.fields < 2) return;
  FieldGrid fg{grid_.fields, grid_.geom.node_count(), grid_.mass.data(), grid_.grad.data(),
               scenario_.contact.field_friction.data(), comm_.distributed() ? exchange_.counted() : nullptr};
  if (grid_.with_volume) {
    fg.volume = grid_.volume.data();
    fg.min_volume_fraction = scenario_.contact.min_volume_fraction;
    fg.geom = &grid_.geom;
    fg.axisymmetric = dimension_ == Dimension::Axisymmetric;
  }
  // Booked passes add their corrections to grid_.impulse and their frictional parts to
  // grid_.friction_impulse; book_impulses books both with the step's midpoint.
  if (book) apply_grid_contact(fg, vel, kTinyMass, grid_.impulse.data(), grid_.friction_impulse.data());
  else apply_grid_contact(fg, vel, kTinyMass);
}

void MpmSolver::book_impulses(const Vec3* v0, const Vec3* v1) {
  // (The damping work, booked in update_grid, uses its own midpoint (v + v_new) / 2 before the
  // conditions and the second contact pass: the same except at the nodes those touch.)
  // The particles' FLIP kinetic-energy change is sum_I m_I dv_I . (v0_I + v_end_I) / 2 up to the
  // Jensen term (minus half the spread of the increments over a particle's nodes): dv_I = v_end -
  // v0 is the node's whole change in the step, v0 the mapped velocity before any correction. So
  // every impulse of the step, contact or constraint, does the work m c . (v0 + v_end) / 2, with
  // one midpoint for all of them; booked so, the impulses and the nodal forces add up to exactly
  // the grid's kinetic-energy change (the energy identities of the MPM update:
  // Bardenhagen, JCP 180 (2002) 383). Nodes shared with a lower rank are booked there.
  // USAVG books in two parts (first_half_stress_update): the constraints on the mapped velocity
  // with (v0 + v_n) / 2, exactly their kinetic-energy change, and the rest of the step with
  // (v_n + v_end) / 2, the velocity whose strain rate the two stress halves see.
  const Index nall = grid_.geom.node_count() * grid_.fields;
  const bool multi = grid_.fields > 1;
  const std::uint8_t* counted = comm_.distributed() ? exchange_.counted() : nullptr;
  const Index nn = grid_.geom.node_count();
  double bw = 0.0;
  for (const BoundaryImpulse& b : boundary_impulses_)  // serial: a fixed order
    if (!counted || counted[b.node % nn])
      bw += grid_.mass[b.node] * b.change * 0.5 * (v0[b.node][b.axis] + v1[b.node][b.axis]);
  boundary_work_ += comm_.sum(bw);
  if (!multi) return;
  const Vec3* c = grid_.impulse.data();
  const Vec3* ct = grid_.friction_impulse.data();
  double w[2];
  deterministic_sum<2>(0, nall, [&](Index k, double* o) {
    if (counted && !counted[k % nn]) return;
    const double m = grid_.mass[k];
    if (!(m > kTinyMass)) return;
    const Vec3 vmid = 0.5 * (v0[k] + v1[k]);
    o[0] += m * dot(c[k], vmid);
    o[1] += m * dot(ct[k], vmid);
  }, w);
  comm_.sum(w, 2);
  contact_work_ += w[0];
  friction_work_ += w[1];
}

void MpmSolver::update_grid(double dt) {
  // v_I = p_I / m_I; a_I = f_I / m_I - c v_I (damping, thesis seed 000 eq. 5.1); explicit Euler.
  // Contact acts on the mapped velocities and again on the updated ones (grid_contact.hpp); the
  // acceleration handed to the particles is measured from the mapped velocity before contact, so
  // that the particles receive both contact impulses (Nairn, Hammerquist & Smith 2020). The damping
  // work is booked here, the contact and boundary impulses' in book_impulses.
  // Node passes over the active blocks only (active_blocks.hpp); the damping work is summed over
  // every node in a fixed order (its round-off does not depend on which blocks are active).
  const Index nall = grid_.geom.node_count() * grid_.fields;
  const bool multi = grid_.fields > 1;
  if (multi) {
    grid_.impulse.resize(nall);
    grid_.friction_impulse.resize(nall);
  }
  for_each_active_node([&](Index i) {
    const double m = grid_.mass[i];
    grid_.velocity[i] = m > kTinyMass ? (1.0 / m) * grid_.velocity[i] : Vec3{};
    if (multi || usavg_) grid_.accel[i] = grid_.velocity[i];  // kept: the velocity before contact
    if (multi) {
      grid_.impulse[i] = Vec3{};
      grid_.friction_impulse[i] = Vec3{};
    }
    // USAVG: the step goes on from v_n, the constrained velocity of the first half.
    if (usavg_) grid_.velocity[i] = usavg_start_[i];
  });
  if (!usavg_) apply_contact(grid_.velocity.data(), true);
  // Explicit Euler per node; returns the work of the damping force -c m v over the step
  // (midpoint velocity), which is summed only when there is damping.
  auto integrate = [&](Index i) {
    const double m = grid_.mass[i];
    if (!(m > kTinyMass)) {
      grid_.velocity_new[i] = Vec3{};
      return 0.0;
    }
    const Vec3 v = grid_.velocity[i];
    const Vec3 a = (1.0 / m) * grid_.force[i] - damping_ * v;
    grid_.velocity_new[i] = v + dt * a;
    return -dt * damping_ * m * dot(v, 0.5 * (v + grid_.velocity_new[i]));
  };
  if (damping_ > 0.0) {
    double w[1];
    if (comm_.distributed()) {
      // A node shared with other ranks is booked by its lowest sharer (grid_exchange.hpp).
      const std::uint8_t* counted = exchange_.counted();
      const Index nn = grid_.geom.node_count();
      deterministic_sum<1>(0, nall, [&](Index i, double* o) {
        const double dw = integrate(i);
        if (counted[i % nn]) o[0] += dw;
      }, w);
    } else {
      // One expression, as before the ranks: the compiler contracts it alike, so serial results
      // stay bitwise what they were.
      deterministic_sum<1>(0, nall, [&](Index i, double* o) { o[0] += integrate(i); }, w);
    }
    damping_work_ += comm_.sum(w[0]);
  } else {
    for_each_active_node([&](Index i) { integrate(i); });
  }
  boundary_impulses_.clear();
  apply_velocity_bcs(grid_.velocity_new.data(), &boundary_impulses_);
  if (multi) {
    apply_contact(grid_.velocity_new.data(), true);
    apply_velocity_bcs(grid_.velocity_new.data(), &boundary_impulses_);  // contact may have moved a face node
  }
  if (usavg_) {
    book_impulses(grid_.velocity.data(), grid_.velocity_new.data());  // from v_n
  } else {
    book_impulses(multi ? grid_.accel.data() : grid_.velocity.data(), grid_.velocity_new.data());
  }
  // The acceleration handed to the particles is the constrained change of velocity.
  const bool kept = multi || usavg_;  // the mapped velocity is in accel
  for_each_active_node([&](Index i) {
    const Vec3& v0 = kept ? grid_.accel[i] : grid_.velocity[i];
    grid_.accel[i] = (1.0 / dt) * (grid_.velocity_new[i] - v0);
  });
  if (!patch_.empty()) {  // the hanging nodes follow their masters
    fill_patch_nodes(grid_.velocity_new.data());
    fill_patch_nodes(grid_.accel.data());
  }
  if (!mirror_faces_.empty()) {  // cubic B-spline: the ghosts beyond a mirror face read the image
    fill_mirror_ghosts(grid_.velocity_new.data());
    fill_mirror_ghosts(grid_.accel.data());
  }
}

double MpmSolver::grid_kinetic_energy_change(double dt) {
  // sum_I m_I (|v_I,end|^2 - |v_I,0|^2) / 2 with v_I,0 the mapped velocity before any constraint
  // (v_I,end - dt a_I, as update_grid defines a_I): the nodal forces and impulses, as book_impulses
  // books them, do exactly this work. Every node in a fixed order, each shared node by its lowest
  // sharer.
  const Index nall = grid_.geom.node_count() * grid_.fields;
  const Index nn = grid_.geom.node_count();
  const std::uint8_t* counted = comm_.distributed() ? exchange_.counted() : nullptr;
  double w[1];
  deterministic_sum<1>(0, nall, [&](Index i, double* o) {
    const double m = grid_.mass[i];
    if (!(m > kTinyMass) || (counted && !counted[i % nn])) return;
    const Vec3& v1 = grid_.velocity_new[i];
    const Vec3 v0 = v1 - dt * grid_.accel[i];
    o[0] += 0.5 * m * (dot(v1, v1) - dot(v0, v0));
  }, w);
  return comm_.sum(w[0]);
}

void MpmSolver::velocity_from_momentum() {
  for_each_active_node([&](Index i) {
    const double m = grid_.mass[i];
    grid_.velocity_new[i] = m > kTinyMass ? (1.0 / m) * grid_.velocity[i] : Vec3{};
  });
}

}  // namespace ballista
