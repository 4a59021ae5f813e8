#pragma once
// The single-element verification suite of `ballista verify`: CATALOGUE A1, A2 (no, isotropic and
// kinematic hardening), A3-A5 (Drucker-Prager vertex, hydrostatic cap, load-unload and pore fluid)
// and A6 (objectivity, tangent) for every registered model, through the model's verification hooks
// (MaterialFactory::example, reduce_elastic, reduce_j2, reduce_geo).
#include <string>
#include <vector>

#include "materials/material.hpp"
#include "verify/verify_case.hpp"

namespace ballista {

/// Test ids in report order.
const std::vector<std::string>& verify_test_ids();

struct VerifySuiteOptions {
  std::vector<std::string> models;  ///< only these models (empty: all registered)
  std::vector<std::string> tests;   ///< only these test ids (empty: all)
  int threads = 0;                  ///< tests run concurrently on this many threads (0: all)
};

/// Runs the suite on `factories` (normally material_registry()). A test that throws (a model
/// error, a non-finite stress) is recorded as failed with the message; the others still run.
/// Throws Error for an unknown model or test name in the options.
std::vector<VerifyCase> run_verify_suite(const std::vector<MaterialFactory>& factories,
                                         const VerifySuiteOptions& options = {});

/// One test of one model (id from verify_test_ids()), with its wall_seconds (0 if not applicable).
VerifyCase run_verify_test(const MaterialFactory& f, const std::string& test);

}  // namespace ballista
