#include "run/sweep_cli.hpp"

#include <filesystem>
#include <iostream>

#include "run/sweep.hpp"
#include "run/sweep_penetration_fit.hpp"

namespace ballista {

namespace fs = std::filesystem;

int run_sweep_cli(const SweepCliOptions& c, const std::string& argv0) {
  SweepOptions o;
  o.deck = c.deck;
  o.vary = c.vary;
  o.set = c.set;
  o.out_dir = c.out_dir.empty() ? fs::path("out") / (fs::path(c.deck).stem().string() + "_sweep") : fs::path(c.out_dir);
  o.jobs = c.jobs;
  o.quiet = c.quiet;
  o.post_steps.push_back(sweep_penetration_post_step());  // U = a + bV when the runs measure penetration
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);  // the running binary, whatever the PATH
  o.executable = ec ? fs::absolute(argv0).string() : self.string();
  try {
    const SweepTable t = run_sweep(o);
    const int failed = t.failed();
    std::cout << (failed ? "FAILED" : "completed") << ": " << t.rows().size() - failed << " of " << t.rows().size()
              << " runs completed\n"
              << "table in " << fs::absolute(o.out_dir / "sweep.csv").string() << "\n";
    if (failed) {
      std::cerr << failed << " run(s) failed:\n";
      for (const auto& r : t.rows())
        if (r.status != "completed")
          std::cerr << "  run_" << r.index << ": " << r.error.substr(0, r.error.find('\n')) << "\n";
    }
    return failed ? 3 : 0;
  } catch (const SweepDeckError& e) {
    std::cerr << "deck error: " << e.what() << "\n";
    return 2;
  } catch (const DeckError& e) {  // a malformed --set (parse_override)
    std::cerr << "deck error: " << e.what() << "\n";
    return 2;
  } catch (const Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace ballista
