// The deck's mpm.* parameters: names, units, defaults and ranges (docs/deck.md).
#include "mpm/mpm_params.hpp"

namespace ballista {

std::vector<ParamSpec> mpm_params() {
  ParamSpec shape{"shape_function", "-", "particle-grid shape functions (docs/deck.md)", false, 0};
  shape.choices = shape_kind_names();
  shape.default_choice = "linear";
  ParamSpec update{"update", "-",
                   "usl, musl (modified USL: robust against cell-crossing at free surfaces) or usavg (half the stress "
                   "update before the forces, half after: energy-consistent)", false, 0};
  update.choices = {"usl", "musl", "usavg"};
  update.default_choice = "musl";
  ParamSpec flip{"flip", "1", "FLIP fraction of the velocity update (1 FLIP, 0 PIC)", false, 1.0, 0.0, 1.0};
  ParamSpec sort{"sort_every", "steps", "steps between particle sorts by cell (0 = never)", false, 20, 0, 2147483647.0};
  sort.integer = true;
  ParamSpec rebalance{"rebalance_imbalance", "1",
                      "several MPI ranks: repartition (Zoltan RCB) when the largest rank holds more than (1 + this) "
                      "times the mean particle count",
                      false, 0.1, 0.0, 100.0};
  ParamSpec locking{"anti_locking", "-",
                    "none, or fbar: cell-averaged volumetric deformation against locking at nu -> 0.5 (Coombs et al., "
                    "CMAME 333 (2018) 1)",
                    false, 0};
  locking.choices = anti_locking_names();
  locking.default_choice = "none";
  ParamSpec patch{"fbar_patch", "cells",
                  "edge of the F-bar's averaging patch in grid cells (anti_locking: fbar): 1 averages over each cell; "
                  "k > 1 over fixed blocks of k x k (x k) cells, the F-bar patch of de Souza Neto, Pires & Owen, IJNME "
                  "62 (2005) 353",
                  false, 1, 1, 8};
  patch.integer = true;
  ParamSpec xpic{"xpic_order", "1",
                 "order m of XPIC for the PIC share (1 - flip) of the update: 1 = PIC; m > 1 keeps the part of the "
                 "particle velocities the grid can carry (Hammerquist & Nairn, CMAME 318 (2017) 724)",
                 false, 1, 1, 8};
  xpic.integer = true;
  ParamSpec bv_linear{"bulk_viscosity_linear", "1",
                      "C_L of the artificial bulk viscosity q = rho l |tr D| (C_L c + C_Q l |tr D|) in "
                      "compression, l the cell size (Wilkins, J. Comput. Phys. 36 (1980) 281): 0 = off; LS-DYNA "
                      "0.06, Uintah 0.2",
                      false, 0.0, 0.0, 10.0};
  ParamSpec bv_quadratic{"bulk_viscosity_quadratic", "1",
                         "C_Q of the artificial bulk viscosity (see bulk_viscosity_linear): 0 = off; LS-DYNA 1.5, "
                         "Uintah 2.0",
                         false, 0.0, 0.0, 100.0};
  ParamSpec bv_speed{"bulk_viscosity_sound_speed", "-",
                     "the sound speed c of the linear term of the bulk viscosity: current (the point's own, Wilkins "
                     "1980) or reference (at the point's J and state with its EOS energy at zero: heat the viscosity "
                     "put in does not raise the coefficient of the next compression)",
                     false, 0};
  bv_speed.choices = {"current", "reference"};
  bv_speed.default_choice = "current";
  ParamSpec distortion{"distortion_limit", "1",
                       "RMS isochoric stretch sqrt(tr(F^T F) / (3 J^(2/3))) beyond which a particle of a hypoelastic "
                       "or fluid material has F replaced by J^(1/3) R (J and the stress frame kept; its stretch "
                       "history, which such models do not read, dropped): material flowing like a fluid otherwise "
                       "stretches until det F and the polar decomposition are lost to round-off. 0 = never",
                       false, 1000.0, 0.0, 1e12};
  // A word, so that its default (none) keeps the physics fingerprint of decks written before it.
  ParamSpec multirate{"multirate", "-",
                      "multi-rate stepping: the most substeps the fastest points take per step of the others (none = "
                      "one step for every point; 2 to 64: points whose own stable step is that many times the "
                      "fastest point's, and not within two cells of a faster point, step that much longer; "
                      "update: usavg only; docs/deck.md)",
                      false, 0};
  multirate.choices = {"none", "2", "4", "8", "16", "32", "64"};
  multirate.default_choice = "none";
  return {shape,        update,   flip, sort, locking, patch, rebalance, xpic, bv_linear, bv_quadratic, bv_speed,
          distortion, multirate};
}

MpmParams read_mpm_params(const ParamValues& P) {
  MpmParams m;
  m.shape = parse_shape_kind(P.choices.at("shape_function"));
  const std::string& update = P.choices.at("update");
  m.update = update == "musl" ? MpmParams::Update::Musl
             : update == "usavg" ? MpmParams::Update::Usavg
                                 : MpmParams::Update::Usl;
  m.flip = P.at("flip");
  m.sort_every = static_cast<int>(P.at("sort_every"));
  m.anti_locking = parse_anti_locking(P.choices.at("anti_locking"));
  m.fbar_patch = static_cast<int>(P.at("fbar_patch"));
  m.rebalance_imbalance = P.at("rebalance_imbalance");
  m.xpic_order = static_cast<int>(P.at("xpic_order"));
  m.bulk_viscosity = {P.at("bulk_viscosity_linear"), P.at("bulk_viscosity_quadratic"),
                      P.choices.at("bulk_viscosity_sound_speed") == "reference"};
  m.distortion_limit = P.at("distortion_limit");
  const std::string& multirate = P.choices.at("multirate");
  m.multirate_max_ratio = multirate == "none" ? 1 : std::stoi(multirate);
  return m;
}

}  // namespace ballista
