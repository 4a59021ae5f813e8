#pragma once
// Explicit Material Point Method (Sulsky, Chen & Schreyer, CMAME 118 (1994) 179; update-stress-
// last and modified-USL as in Nairn, CMES 4 (2003) 649 and Buzzi et al. 2008), the solver of the
// thesis seed 000 (ch. 5-6, run there in Uintah). One velocity field on the grid for all bodies,
// which gives no-slip contact for free.
#include <atomic>
#include <memory>
#include <vector>

#include "core/communicator.hpp"
#include "core/solver.hpp"
#include "io/scenario.hpp"
#include "materials/material.hpp"
#include "mpm/grid_geometry.hpp"
#include "mpm/shape_functions.hpp"

namespace ballista {

/// Grid arrays of one block (nodal mass, momentum/velocity, force).
struct GridData {
  GridGeometry geom;
  std::vector<double> mass;      ///< kg
  std::vector<Vec3> velocity;    ///< m/s: momentum during P2G, then velocity at t_n
  std::vector<Vec3> force;       ///< N: internal + external during P2G
  std::vector<Vec3> velocity_new;///< m/s at t_{n+1} after boundary conditions
  std::vector<Vec3> accel;       ///< m/s^2 over the step (after boundary conditions)
  void resize(Index n) {
    mass.assign(n, 0.0);
    velocity.assign(n, Vec3{});
    force.assign(n, Vec3{});
    velocity_new.assign(n, Vec3{});
    accel.assign(n, Vec3{});
  }
};

/// A PhysicsError about one particle; carries its id so that the run can be repeated with that
/// particle tracked (`ballista run --track-failed`, output.track.ids).
class ParticleError : public PhysicsError {
 public:
  ParticleError(std::int64_t id, const std::string& message) : PhysicsError(message), id_(id) {}
  std::int64_t id() const { return id_; }

 private:
  std::int64_t id_;
};

class MpmSolver final : public Solver {
 public:
  MpmSolver(const Scenario& scenario, std::vector<std::unique_ptr<Material>> materials,
            Communicator comm = {});

  const char* name() const override { return "mpm"; }
  double stable_dt() override;
  void step(double dt) override;
  double time() const override { return time_; }
  long steps() const override { return steps_; }
  FieldStore& points() override { return points_; }
  EnergyTotals energies() const override;
  double reporting_scale() const override;
  void begin_stage(int stage, double damping) override;
  StepLimiter step_limiter() const override;

  const GridData& grid() const { return grid_; }
  const std::vector<std::unique_ptr<Material>>& materials() const { return materials_; }
  /// Number of points seeded but not yet active (bodies with a later activation_time).
  Index pending_points() const { return pending_.size(); }

 private:
  void activate_pending();
  void sort_by_cell();
  void build_slabs();
  void compute_external_forces();
  template <int Dim, ShapeKind K> void step_impl(double dt);
  template <int Dim, ShapeKind K> void particles_to_grid(bool momentum_only);
  template <int Dim, ShapeKind K> void grid_to_particles(double dt);
  template <int Dim, ShapeKind K> void velocity_gradient_from_grid(double dt);
  void finish_point(Index p, const Mat3& l, const Vec3& disp, double dt, std::atomic<Index>& bad,
                    std::atomic<Index>& out);
  void bind_fields();
  void ensure_material_groups();
  void update_stress(double dt);
  void update_grid(double dt);
  void apply_velocity_bcs(std::vector<Vec3>& vel);
  /// Throws a DeckError if the grid and the bodies' points cannot fit in the memory available.
  void check_memory(const Scenario& sc, double nodes) const;
  void handle_exits();
  [[noreturn]] void fail(Index p, const std::string& what) const;
  int stencil_reach_now() const;

  Scenario scenario_;
  std::vector<std::unique_ptr<Material>> materials_;
  Communicator comm_;
  Dimension dimension_;
  int dim_;
  ShapeKind shape_;
  bool musl_;
  double flip_;
  double damping_;
  GridData grid_;
  Vec3 box_lower_, box_upper_;  ///< physical grid box (without ghost layers)
  int ghost_ = 3;               ///< ghost node layers beyond the box on each side
  int box_first_[3], box_last_[3];  ///< node index range of the physical box per axis
  FieldStore points_;
  FieldStore pending_;          ///< seeded points of bodies not yet active
  std::vector<double> pending_activation_;  ///< activation time of each pending point (from its stage start)
  std::vector<int> pending_stage_;          ///< stage whose start begins each pending point's clock
  std::vector<double> stage_start_;         ///< s: start time of each stage (infinite until it begins)
  std::vector<Vec3> fext_;      ///< external force on each point this step, N (all loads; for the work)
  std::vector<Vec3> ftrac_;     ///< the surface-traction part of fext_, N (spread from surface points)
  struct SurfaceForce {
    Vec3 point;  ///< m: where the traction acts (the particle's face on the loaded surface)
    Vec3 force;  ///< N
  };
  std::vector<SurfaceForce> surface_forces_;
  std::vector<Vec3> displacement_;  ///< MUSL: dt * grid velocity at each point this step, m
  bool groups_dirty_ = true;    ///< material_points_ must be rebuilt (points reordered/removed)
  Index first_bad_ = 0, first_out_ = 0;  ///< lowest inverted / escaped point of the step (or n)
  // Field pointers bound at the start of each step (valid until points are reordered).
  Vec3* x_ = nullptr;
  Mat3* F_ = nullptr;
  Mat3* L_ = nullptr;
  double* vol_ = nullptr;
  const double* vol0_ = nullptr;
  std::vector<std::vector<Index>> material_points_;  ///< indices per material
  std::vector<Index> slab_start_, slab_points_;      ///< CSR lists of point indices per slab
  std::vector<int> slab_of_point_;                   ///< scratch: slab of each point
  std::vector<Index> slab_fill_;                     ///< scratch: fill cursor per slab
  std::vector<Index> sort_key_, sort_start_, sort_order_;  ///< scratch of sort_by_cell
  int slab_axis_ = 2, slab_width_ = 2;
  double time_ = 0.0;
  long steps_ = 0;
  double external_work_ = 0.0;  ///< per-point sum (not yet scaled)
  double removed_mass_ = 0.0, removed_energy_ = 0.0;
  double inserted_energy_ = 0.0;  ///< per-point sum of the energy of activated points (this rank)
  Vec3 removed_momentum_;
  std::vector<std::string> load_area_fields_;
};

}  // namespace ballista
