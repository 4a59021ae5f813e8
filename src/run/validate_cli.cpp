#include "run/validate_cli.hpp"

#include <filesystem>
#include <iostream>

#include "core/data_dir.hpp"
#include "io/python_tool.hpp"

namespace ballista {

namespace fs = std::filesystem;

int run_validate_cli(const ValidateCliOptions& o, const char* argv0) {
  const std::string self = executable_path();  // the running binary, whatever the PATH
  const std::string exe = self.empty() ? fs::absolute(argv0).string() : self;
  const fs::path root = data_dir();
  const fs::path catalogue = root / "data" / "validation_catalogue.yaml";
  if (!fs::exists(catalogue)) {
    std::cerr << "validate: the catalogue " << catalogue.string() << " is missing (looked in the "
              << data_dir_origin() << " data directory; set " << kDataDirEnv << " to the directory holding data/)\n";
    return 2;
  }
  std::vector<std::string> args = {"--ballista", exe, "--catalogue", catalogue.string(), "--root", root.string(),
                                   "-o", o.out_dir, "--level", o.level};
  for (const std::string& id : o.only) {
    args.push_back("--only");
    args.push_back(id);
  }
  for (const std::string& id : o.skip) {
    args.push_back("--skip");
    args.push_back(id);
  }
  if (o.list) args.push_back("--list");
  if (o.threads > 0) {
    args.push_back("--threads");
    args.push_back(std::to_string(o.threads));
  }
  int status = 0;
  const std::string err = run_python_tool_status("validate.py", args, status, "the V&V report");
  if (!err.empty()) {
    std::cerr << "validate: " << err << "\n";
    return 2;
  }
  return status < 0 ? 2 : status;
}

}  // namespace ballista
