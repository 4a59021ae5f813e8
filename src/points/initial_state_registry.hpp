#pragma once
// Registry of initial states (bodies[].initial_state), like the load registry: each kind sets the
// state of a body's points right after seeding from its own file (BALLISTA_REGISTER_INITIAL_STATE,
// files in points/initial_states/). The deck reader, `ballista info` and the seeding read it.
#include <optional>
#include <string>
#include <vector>

#include "core/field_store.hpp"
#include "core/registry.hpp"
#include "materials/material.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Why a body cannot take an initial state: the body's key to blame and the message.
struct BodyIssue {
  std::string key;
  std::string message;
};

struct InitialStateFactory {
  std::string name;         ///< bodies[].initial_state ("none" is the default and no kind)
  std::string description;  ///< one line, with its source
  /// What the state needs of the body (shape, velocity); the deck reader reports it. May be null.
  std::optional<BodyIssue> (*check)(const BodySpec& body) = nullptr;
  /// Sets the state of the body's points [first, last) just seeded (velocity, F, stress...).
  void (*apply)(const BodySpec& body, const Material& material, FieldStore& points, Index first,
                Index last) = nullptr;
};

/// Registered initial states by name (core/registry.hpp), filled at static-initialisation time.
using InitialStateRegistry = Registry<InitialStateFactory, &InitialStateFactory::name>;
inline const std::vector<InitialStateFactory>& initial_state_registry() { return InitialStateRegistry::sorted(); }
inline const InitialStateFactory* find_initial_state(const std::string& name) {
  return InitialStateRegistry::find(name);
}

}  // namespace ballista

/// Registers one from its own .cpp: BALLISTA_REGISTER_INITIAL_STATE(InitialStateFactory{...}).
#define BALLISTA_REGISTER_INITIAL_STATE(...) BALLISTA_REGISTER(::ballista::InitialStateRegistry, __VA_ARGS__)
