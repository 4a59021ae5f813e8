#include "verify/verify_suite.hpp"

#include <algorithm>
#include <chrono>
#include <exception>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "verify/a1_frame_indifference.hpp"
#include "verify/a2_uniaxial_strain.hpp"
#include "verify/a3_drucker_prager_vertex.hpp"
#include "verify/a4_hydrostatic_cap.hpp"
#include "verify/a5_load_unload.hpp"
#include "verify/a6_objectivity.hpp"
#include "verify/a7_misaligned_rate.hpp"
#include "verify/a8_uniaxial_strain_cap.hpp"

namespace ballista {

const std::vector<std::string>& verify_test_ids() {
  static const std::vector<std::string> ids{"A1", "A2", "A2-iso", "A2-kin", "A3", "A4", "A5", "A5-fluid",
                                            "A6-objectivity", "A6-tangent", "A7", "A8"};
  return ids;
}

namespace {

VerifyCase dispatch(const MaterialFactory& f, const std::string& test) {
  if (test == "A1") return run_a1(f);
  if (test == "A2") return run_a2(f, A2Hardening::None);
  if (test == "A2-iso") return run_a2(f, A2Hardening::Isotropic);
  if (test == "A2-kin") return run_a2(f, A2Hardening::Kinematic);
  if (test == "A3") return run_a3(f);
  if (test == "A4") return run_a4(f);
  if (test == "A5") return run_a5(f);
  if (test == "A5-fluid") return run_a5_fluid(f);
  if (test == "A6-objectivity") return run_a6_objectivity(f);
  if (test == "A6-tangent") return run_a6_tangent(f);
  if (test == "A7") return run_a7(f);
  if (test == "A8") return run_a8(f);
  throw Error("unknown verification test '" + test + "'");
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

}  // namespace

VerifyCase run_verify_test(const MaterialFactory& f, const std::string& test) {
  // Every test is timed here, one way for all (each test used to carry its own copy of the clock).
  const auto t0 = std::chrono::steady_clock::now();
  VerifyCase c = dispatch(f, test);
  if (c.status != VerifyStatus::NotApplicable)
    c.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return c;
}

std::vector<VerifyCase> run_verify_suite(const std::vector<MaterialFactory>& factories,
                                         const VerifySuiteOptions& opt) {
  std::vector<std::string> names;
  for (const auto& f : factories) names.push_back(f.model);
  for (const auto& m : opt.models)
    if (std::find(names.begin(), names.end(), m) == names.end())
      throw Error("verify: unknown model '" + m + "' (registered: " + join(names) + ")");
  for (const auto& t : opt.tests)
    if (std::find(verify_test_ids().begin(), verify_test_ids().end(), t) == verify_test_ids().end())
      throw Error("verify: unknown test '" + t + "' (tests: " + join(verify_test_ids()) + ")");

  struct Job {
    const MaterialFactory* f;
    std::string test;
  };
  std::vector<Job> jobs;
  for (const auto& f : factories) {
    if (!opt.models.empty() && std::find(opt.models.begin(), opt.models.end(), f.model) == opt.models.end()) continue;
    for (const auto& t : verify_test_ids())
      if (opt.tests.empty() || std::find(opt.tests.begin(), opt.tests.end(), t) != opt.tests.end())
        jobs.push_back({&f, t});
  }
  // Tests are independent single-point runs (serial inside: a handful of points never reaches
  // the parallel threshold of Material::update), so they run concurrently, one per thread.
  std::vector<VerifyCase> out(jobs.size());
  const int threads = opt.threads > 0 ? opt.threads : max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (Index k = 0; k < static_cast<Index>(jobs.size()); ++k) {
    const Job& j = jobs[static_cast<size_t>(k)];
    try {
      out[k] = run_verify_test(*j.f, j.test);
    } catch (const std::exception& e) {
      VerifyCase c;
      c.model = j.f->model;
      c.test = j.test;
      c.title = j.test;
      c.status = VerifyStatus::Fail;
      c.reason = std::string("error: ") + e.what();
      out[k] = std::move(c);
    }
  }
  return out;
}

}  // namespace ballista
