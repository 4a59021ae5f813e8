# The layers of src/: one static library per folder, ballista_<layer>, built from every .cpp in
# the folder (a file added to a folder joins its layer at the next build: CONFIGURE_DEPENDS).
# Each layer links only the layers it is allowed to use (PUBLIC, so what they use comes too).
# This list is the dependency rule of docs/architecture.md, written once:
#  - tests/architecture/check_layers.py (ctest `architecture.layers`) fails on any
#    #include "<layer>/..." in src/ that this graph does not allow (headers all live under one
#    include root, so the compiler alone would not notice an upward include);
#  - layer_link_check_<layer> links each layer's whole archive with only the layers below it,
#    so an upward call fails to link during the build.
# A new folder in src/ must be declared here; the architecture test fails until it is.

# The standard and third-party headers most library files include, parsed once into a
# precompiled header that every layer reuses: on two cores the build is most of `make test`, and
# these headers (spdlog and yaml-cpp about a second each) were a third of a library file's
# compile time. Only headers from outside src/, so that a change to a project header rebuilds
# what includes it and nothing more; a file still includes what it uses (the header only saves
# parsing it again).
add_library(ballista_pch_owner OBJECT ${PROJECT_SOURCE_DIR}/cmake/pch_owner.cpp)
target_link_libraries(ballista_pch_owner PRIVATE ballista_common)
target_precompile_headers(ballista_pch_owner PRIVATE
  <algorithm> <array> <cmath> <cstdint> <cstdio> <filesystem> <functional> <map> <memory> <optional>
  <string> <vector> <fmt/format.h> <spdlog/spdlog.h> <yaml-cpp/yaml.h>)

# The layers without numerical kernels (the deck reader, the writers, the run loop's bookkeeping,
# the verification catalogue, the post-processing) are compiled as unity batches of 8 files: their
# files share most of their headers (the deck, the scenario, the solvers' interfaces), and a batch
# parses them once; these six layers' compile time fell to about a third, the whole build's by about
# 30 % (docs/validation.md, "What `make test` costs"). The numerical layers are not batched: a
# batch lets the compiler inline one file's functions into another's, and with -march=native's FMA
# contraction that may change the rounding of results. Every example's results were compared
# bitwise with the file-by-file build (tools/compare_builds.py). A name a file keeps to itself must
# be unique in its layer.
set(BALLISTA_UNITY_LAYERS run deck io verify analysis penetration)

# ballista_layer(<name> [DEPENDS <lower layer>...])
function(ballista_layer name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "DEPENDS")
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${name}/*.cpp)
  add_library(ballista_${name} STATIC ${sources})
  target_link_libraries(ballista_${name} PUBLIC ballista_common)
  target_precompile_headers(ballista_${name} REUSE_FROM ballista_pch_owner)
  if(name IN_LIST BALLISTA_UNITY_LAYERS)
    set_target_properties(ballista_${name} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
    # GCC 12's -O3 inlining of `"literal" + std::string&&` across a batch warns of a memcpy bound
    # or offset beyond the largest object, known false positives (GCC bugs 105329 and 105651).
    target_compile_options(ballista_${name} PRIVATE
                           $<$<CXX_COMPILER_ID:GNU>:-Wno-stringop-overflow -Wno-array-bounds>)
  endif()
  foreach(dep IN LISTS arg_DEPENDS)
    if(NOT TARGET ballista_${dep})
      message(FATAL_ERROR "layer ${name}: '${dep}' is not a layer declared before it")
    endif()
    # Whole archive here too: CMake refuses a library linked both with and without the feature,
    # and every user of a layer wants its registrations kept.
    target_link_libraries(ballista_${name} PUBLIC "$<LINK_LIBRARY:WHOLE_ARCHIVE,ballista_${dep}>")
  endforeach()
  # "name=dep,dep" entries for the include check.
  string(REPLACE ";" "," deps "${arg_DEPENDS}")
  set_property(GLOBAL APPEND PROPERTY BALLISTA_LAYER_GRAPH "${name}=${deps}")
  set_property(GLOBAL APPEND PROPERTY BALLISTA_LAYERS ballista_${name})
endfunction()

# Bottom to top. Why this order (docs/architecture.md): io holds the writers (CSV, JSON, HDF5,
# checkpoints, the results folder) on core alone, so a layer that writes needs nothing else; the registries
# (materials; solvers, probes, loads and initial states in points) sit below deck, so the deck
# reader validates against them without naming an implementation.
ballista_layer(core)
ballista_layer(io DEPENDS core)
ballista_layer(materials DEPENDS core)
ballista_layer(scenario DEPENDS materials)
ballista_layer(geometry DEPENDS scenario)
ballista_layer(points DEPENDS geometry)
ballista_layer(mpm DEPENDS points)
ballista_layer(peridynamics DEPENDS points)
ballista_layer(otm DEPENDS points)
ballista_layer(deck DEPENDS points)
ballista_layer(penetration DEPENDS io)
ballista_layer(analysis DEPENDS deck penetration)
ballista_layer(driver DEPENDS deck io)
ballista_layer(verify DEPENDS driver)
ballista_layer(run DEPENDS analysis driver)

get_property(BALLISTA_LAYER_LIBS GLOBAL PROPERTY BALLISTA_LAYERS)
get_property(BALLISTA_LAYER_GRAPH GLOBAL PROPERTY BALLISTA_LAYER_GRAPH)

# Everything, for the CLI, the tests and the benchmarks. Models, solvers and probes register
# themselves from their own file (static initialisers) that nothing references: link the whole
# archives so the linker keeps them.
add_library(ballista_all INTERFACE)
foreach(lib IN LISTS BALLISTA_LAYER_LIBS)
  target_link_libraries(ballista_all INTERFACE "$<LINK_LIBRARY:WHOLE_ARCHIVE,${lib}>")
endforeach()

# Link check: every object of a layer with only the layers it may use. A call into a higher
# layer (even through a forward declaration, which the include check cannot see) is then an
# undefined reference and the build stops here.
option(BALLISTA_LAYER_LINK_CHECK "Link each layer alone with the layers below it" ON)
if(BALLISTA_LAYER_LINK_CHECK)
  foreach(lib IN LISTS BALLISTA_LAYER_LIBS)
    add_executable(layer_link_check_${lib} ${PROJECT_SOURCE_DIR}/cmake/layer_link_check.cpp)
    target_link_libraries(layer_link_check_${lib} PRIVATE "$<LINK_LIBRARY:WHOLE_ARCHIVE,${lib}>")
    set_target_properties(layer_link_check_${lib} PROPERTIES RUNTIME_OUTPUT_DIRECTORY
                          ${CMAKE_BINARY_DIR}/layer_link_check)
  endforeach()
endif()
