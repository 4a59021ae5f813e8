// Timing driver for LGR's OTM solver on the copper Taylor bar (bench/peers/lgr_otm_taylor.sh).
// Project code that links against an LGR build (lgrlib); it calls LGR's public OTM functions with
// the set-up sequence of LGR's own otm_taylor() app, but reads the mesh path, end time and
// numerics from the command line, uses Ballista's material (linear hardening) and writes no files.
//
//   lgr_otm_taylor_driver MESH.g END_TIME [CFL=0.1] [GAMMA=1.5] [MIN_SUPPORT=12]
//
// Prints one line: points nodes avg_support steps sim_time setup_s run_s point_steps_per_s
// (avg_support = mean number of nodes in a point's shape-function support).
#include <hpc_macros.hpp>
#include <lgr_exodus.hpp>
#include <lgr_input.hpp>
#include <lgr_state.hpp>
#include <otm_apps.hpp>
#include <otm_meshless.hpp>
#include <otm_search.hpp>
#include <otm_tet2meshless.hpp>
#include <otm_tetrahedron_util.hpp>
#include <otm_util.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>

int main(int argc, char** argv)
{
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s MESH.g END_TIME [CFL] [GAMMA] [MIN_SUPPORT]\n", argv[0]);
    return 2;
  }
  using namespace lgr;
  using clock = std::chrono::steady_clock;
  std::string const mesh     = argv[1];
  double const      end_time = std::atof(argv[2]);
  double const      cfl      = argc > 3 ? std::atof(argv[3]) : 0.1;
  double const      gamma    = argc > 4 ? std::atof(argv[4]) : 1.5;
  int const         support  = argc > 5 ? std::atoi(argv[5]) : 12;

  otm_scope                scope;
  constexpr material_index body(0);
  input                    in(material_index(1), material_index(0));
  state                    s;
  in.otm_material_points_to_add_per_element = 1;
  tet_nodes_to_points point_interpolator(1);
  in.xp_transform = std::ref(point_interpolator);
  auto const t0   = clock::now();
  if (read_exodus_file(mesh, in, s) != 0) {
    std::fprintf(stderr, "cannot read %s\n", mesh.c_str());
    return 1;
  }
  // Ballista's examples/taylor_bar_otm.yaml: 227 m/s onto the rigid wall (LGR's wall is z = 0).
  in.initial_v = [](hpc::counting_range<node_index> const nodes,
                    hpc::device_array_vector<hpc::position<double>, node_index> const&,
                    hpc::device_array_vector<hpc::velocity<double>, node_index>* v_vector) {
    auto const nodes_to_v = v_vector->begin();
    hpc::for_each(hpc::device_policy(), nodes, [=] HPC_DEVICE(node_index const node) {
      nodes_to_v[node] = hpc::velocity<double>(0.0, 0.0, 227.0);
    });
  };
  in.name                    = "lgr-otm-taylor-bench";
  in.end_time                = end_time;
  in.num_file_output_periods = 0;
  in.do_output               = false;
  in.output_to_command_line  = false;
  in.debug_output            = false;
  // Copper as in Ballista: rho 8930, E 117 GPa, nu 0.35, Y0 400 MPa, linear hardening H = 100 MPa
  // (LGR's power law Y0 (1 + eqps/eps0)^(1/n) is linear for n = 1, eps0 = Y0/H); no rate term.
  auto const rho = hpc::density<double>(8930.0);
  auto const nu  = hpc::adimensional<double>(0.35);
  auto const E   = hpc::pressure<double>(117.0e9);
  auto const Y0  = hpc::pressure<double>(400.0e6);
  auto const H   = hpc::pressure<double>(100.0e6);
  in.minimum_support_size        = support;
  in.materials                   = hpc::counting_range<material_index>(1);
  in.enable_variational_J2[body] = true;
  in.enable_neo_Hookean[body]    = false;
  in.rho0[body]                  = rho;
  in.K0[body]                    = hpc::pressure<double>(E / (3.0 * (1.0 - 2.0 * nu)));
  in.G0[body]                    = hpc::pressure<double>(E / (2.0 * (1.0 + nu)));
  in.Y0[body]                    = Y0;
  in.n[body]                     = hpc::adimensional<double>(1.0);
  in.eps0[body]                  = hpc::strain<double>(Y0 / H);
  in.Svis0[body]                 = hpc::pressure<double>(0.0);
  in.m[body]                     = hpc::adimensional<double>(1.0);
  in.eps_dot0[body]              = hpc::strain_rate<double>(1.0e-01);
  in.CFL                         = cfl;
  in.use_constant_dt             = false;  // stable dt recomputed every step, as in LGR's app
  in.constant_dt                 = hpc::time<double>(1.0e-07);
  in.otm_gamma                   = gamma;
  in.domains[body]               = std::make_unique<clipped_domain<all_space>>(all_space{});
  convert_tet_mesh_to_meshless(in, s);
  search::do_otm_iterative_point_support_search(s, in.minimum_support_size);
  s.otm_gamma                = in.otm_gamma;
  s.dt                       = in.constant_dt;
  s.dt_old                   = in.constant_dt;
  s.time                     = hpc::time<double>(0.0);
  s.max_stable_dt            = in.constant_dt;
  s.num_time_steps           = 0;
  s.use_displacement_contact = true;
  s.use_penalty_contact      = false;
  s.contact_penalty_coeff    = hpc::strain_rate_rate<double>(1.0e14);
  otm_allocate_state(in, s);
  s.prescribed_v[body]   = hpc::velocity<double>(0.0, 0.0, 0.0);
  s.prescribed_dof[body] = hpc::vector3<int>(0, 0, 0);
  hpc::fill(hpc::device_policy(), s.rho, rho);
  hpc::fill(hpc::device_policy(), s.F_total, hpc::deformation_gradient<double>::identity());
  hpc::fill(hpc::device_policy(), s.Fp_total, hpc::deformation_gradient<double>::identity());
  hpc::fill(hpc::device_policy(), s.ep, hpc::strain<double>(0.0));
  hpc::fill(hpc::device_policy(), s.b, hpc::acceleration<double>::zero());
  otm_initialize(in, s);
  auto max_of = [](auto const& v) {
    hpc::length<double> init{0};
    return hpc::transform_reduce(hpc::device_policy(), v, init, hpc::maximum<hpc::length<double>>(),
                                 hpc::identity<hpc::length<double>>());
  };
  in.enable_adapt                = false;
  in.max_node_neighbor_distance  = max_of(s.nearest_node_neighbor_dist);
  in.max_point_neighbor_distance = max_of(s.nearest_point_neighbor_dist);
  auto const t1 = clock::now();
  otm_run(in, s);
  auto const t2 = clock::now();

  double const setup  = std::chrono::duration<double>(t1 - t0).count();
  double const run    = std::chrono::duration<double>(t2 - t1).count();
  long const   points = long(s.points.size());
  long const   nodes  = long(s.nodes.size());
  long const   steps  = long(s.n);
  double const supp   = double(s.point_nodes_to_nodes.size()) / double(points);
  std::cout.unsetf(std::ios::floatfield);
  std::cout << "RESULT points " << points << " nodes " << nodes << " avg_support " << supp << " steps " << steps << " sim_time "
            << double(s.time) << " setup_s " << setup << " run_s " << run << " point_steps_per_s "
            << double(points) * double(steps) / run << std::endl;
  return 0;
}
