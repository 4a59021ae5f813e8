#pragma once
// Fragments of a peridynamic body (seed 001, "fragmentation V&V": fragment mass and velocity
// distributions): the connected components of the points over the intact bonds, found by
// union-find. A point with no intact bond left is a fragment of its own.
#include <vector>

#include "core/communicator.hpp"
#include "core/field_store.hpp"
#include "core/tensor.hpp"
#include "peridynamics/bond_family.hpp"

namespace ballista::pd {

struct Fragment {
  Index points = 0;     ///< number of points
  double mass = 0.0;    ///< kg
  Vec3 center;          ///< centre of mass, m
  Vec3 velocity;        ///< centre-of-mass velocity, m/s
  double kinetic_energy = 0.0;  ///< 1/2 M |V|^2 of the centre-of-mass motion, J
  Index first_point = 0;        ///< lowest point index in it (a stable label)
};

/// Fragments of the points of `store` (fields x, v, mass) bonded by the intact bonds of `bonds`,
/// largest mass first (ties: lowest first point). Points whose damage (pd::kBondDamage) exceeds
/// `damage_threshold` are left out (dust, not fragments); the default keeps every point. Points
/// with skip[p] != 0 (detonation products) are never part of a fragment.
std::vector<Fragment> find_fragments(const BondFamily& bonds, const FieldStore& store,
                                     double damage_threshold = 2.0, const std::uint8_t* skip = nullptr);

/// Several ranks (collective): the fragments of every rank's own points, found on rank 0
/// over the points gathered in id order and their intact bonds (each sent once, from its lower-id
/// end), so they are the serial run's, bit for bit; empty on the other ranks. `own[i]` is the row
/// in `bonds` of the store's point i, `ids` the ids of the rows' points; points of a material m
/// with skip_material[m] != 0 (detonation products) are never part of a fragment.
std::vector<Fragment> find_fragments_gathered(const Communicator& comm, const BondFamily& bonds,
                                              const std::vector<Index>& own, const std::int64_t* ids,
                                              const FieldStore& store, double damage_threshold,
                                              const std::vector<std::uint8_t>& skip_material = {});

}  // namespace ballista::pd
