// `fleetmerge example DIR --octree`: the 3-D counterpart of the example pair, for trying octree
// merging without 3-D data. A seeded synthetic office at 10 cm, extruded to one storey
// (octree/synthetic_octree.hpp), cut into two overlapping robot maps as in the 2-D example; each
// robot's octree frame also sits at a random height. Writes robot_a.bt, robot_b.bt, truth.yaml
// (the true pose of b's frame in a's, with z) and job.yaml, ready for `fleetmerge merge`.
#pragma once

#include <iosfwd>

#include "cli/example_command.hpp"

namespace fleetmerge {

int RunOctreeExample(const ExampleCommand& command, std::ostream& out);

}  // namespace fleetmerge
