// The MPM solver's state beyond the point fields for a checkpoint: clock, energy terms and, on
// several ranks, the decomposition.
#include "mpm/mpm_solver.hpp"

namespace ballista {

void MpmSolver::save_state(StateArchive& a) const {
  pts_.save_state(a);  // several ranks: collective, every rank's particles in rank 0's archive
  a.put_real("mpm.time", time_);
  a.put_int("mpm.steps", steps_);
  a.put("mpm.work", std::vector<double>{external_work_, damping_work_, contact_work_, friction_work_,
                                        transfer_work_, damping_});
  a.put_real("mpm.boundary_work", boundary_work_);
  // Collective (as pts_.save_state): the total heat and the largest speed of every rank.
  a.put("mpm.bulk_viscosity", std::vector<double>{comm_.sum(viscous_work_), comm_.max(viscous_speed_)});
  if (scenario_.grid.graded()) a.put_real("mpm.viscous_rate", viscous_rate_);  // one rank (graded grids)
  if (multirate_max_ > 1) {
    const MultirateTally& t = multirate_tally_;
    a.put("mpm.multirate_tally",
          std::vector<double>{t.steps, t.substeps, t.fast_point_steps, t.slow_point_steps, t.single_rate_point_steps});
  }
  if (comm_.distributed()) {
    // The decomposition: the region boxes (a restart on as many ranks migrates exactly as the
    // uninterrupted run) and rank 0's statistics.
    a.put("mpm.rcb_boxes", partition_.boxes());
    a.put("mpm.decomposition", std::vector<double>{static_cast<double>(repartitions_), migrated_, halo_bytes_,
                                                   halo_messages_, halo_steps_, max_imbalance_,
                                                   imbalance_after_partition_});
  }
}

void MpmSolver::load_state(const StateArchive& a) {
  const bool own = pts_.load_state(a);
  if (comm_.distributed()) {
    const std::size_t nbox = static_cast<std::size_t>(6 * comm_.size());
    if (own && a.has("mpm.rcb_boxes") && a.reals("mpm.rcb_boxes").size() == nbox) {
      // Written on as many ranks: each rank has its particles back in their order, and the cuts.
      partition_.restore_boxes(a.reals("mpm.rcb_boxes", nbox));
      double repartitions = 0.0;
      a.get_into("mpm.decomposition", {&repartitions, &migrated_, &halo_bytes_, &halo_messages_, &halo_steps_,
                                       &max_imbalance_, &imbalance_after_partition_});
      repartitions_ = static_cast<long>(repartitions);
    } else {
      // Another rank count (or a serial checkpoint): cut anew and move the particles there.
      cut_and_migrate();
      imbalance_after_partition_ = 0.0;
    }
  }
  time_ = a.real("mpm.time");
  steps_ = static_cast<long>(a.integer("mpm.steps"));
  restore_patches_if_due();
  a.get_into("mpm.work",
             {&external_work_, &damping_work_, &contact_work_, &friction_work_, &transfer_work_, &damping_});
  boundary_work_ = a.real("mpm.boundary_work");
  double viscous_work_total = 0.0;
  a.get_into("mpm.bulk_viscosity", {&viscous_work_total, &viscous_speed_});
  viscous_work_ = comm_.rank() == 0 ? viscous_work_total : 0.0;  // held by rank 0 (energies() sums)
  if (scenario_.grid.graded()) viscous_rate_ = a.real("mpm.viscous_rate");
  if (multirate_max_ > 1 && a.has("mpm.multirate_tally")) {
    MultirateTally& t = multirate_tally_;
    a.get_into("mpm.multirate_tally",
               {&t.steps, &t.substeps, &t.fast_point_steps, &t.slow_point_steps, &t.single_rate_point_steps});
  }
}

}  // namespace ballista
