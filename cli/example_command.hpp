// `fleetmerge example DIR`: writes a ready-made test pair with a known answer, made from a
// seeded synthetic office floor: two overlapping robot maps, the second in a frame of its own,
// and truth.yaml with the true pose of b's map frame in a's. The README's quick start runs
// `fleetmerge pair` on it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>

namespace fleetmerge {

struct ExampleCommand {
  std::filesystem::path out_dir;
  std::uint32_t seed = 1;
  bool octree = false;  // --octree: two OctoMap octrees instead (cli/octree_example.hpp)
};

int RunExampleCommand(const ExampleCommand& command, std::ostream& out);

}  // namespace fleetmerge
