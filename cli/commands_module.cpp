#include "cli/commands_module.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>
#include <vector>

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;

constexpr const char* kModuleFile = "libfleetmerge_commands.so";
constexpr const char* kEntryPoint = "fleetmerge_run_all_commands";

std::vector<fs::path> ModuleCandidates() {
  std::vector<fs::path> candidates;
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    candidates.push_back(exe.parent_path() / kModuleFile);
    candidates.push_back(exe.parent_path() / FLEETMERGE_COMMANDS_RELATIVE_DIR / kModuleFile);
  }
  candidates.push_back(fs::path(FLEETMERGE_COMMANDS_INSTALL_DIR) / kModuleFile);
  return candidates;
}

}  // namespace

int RunThroughCommandsModule(int argc, char** argv) {
  std::string searched;
  for (const fs::path& candidate : ModuleCandidates()) {
    std::error_code error;
    if (!fs::exists(candidate, error)) {
      searched += "\n  " + candidate.string();
      continue;
    }
    // Lazy binding, as the executable's own libraries get; local, so that nothing loaded later
    // binds to the module's symbols.
    void* module = dlopen(candidate.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (module == nullptr) {
      std::cerr << "fleetmerge: error: cannot load " << candidate.string() << ": " << dlerror()
                << "\n";
      return 1;
    }
    using EntryPoint = int (*)(int, char**);
    const auto run = reinterpret_cast<EntryPoint>(dlsym(module, kEntryPoint));
    if (run == nullptr) {
      std::cerr << "fleetmerge: error: " << candidate.string() << " has no " << kEntryPoint
                << " (from another fleetmerge version?)\n";
      return 1;
    }
    return run(argc, argv);
  }
  std::cerr << "fleetmerge: error: the commands module " << kModuleFile
            << " is missing (the installation is incomplete); looked for:" << searched << "\n";
  return 1;
}

}  // namespace fleetmerge
