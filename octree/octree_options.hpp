// How an OctoMap octree becomes a 2-D floor plan (octree/octree_projection.hpp). A plain struct
// without OctoMap so that FleetOptions can carry it; filled from a job file's `octree` mapping
// (io/octree_job_keys.hpp) or the command line, and validated there.
#pragma once

namespace fleetmerge {

struct OctreeOptions {
  // The height band, in metres above the estimated floor (octree/floor_height.hpp), whose voxels
  // make the floor plan. 0.3 m clears the floor, skirting and low clutter (cables, door sills);
  // 1.8 m stays under ceilings (2.2 m and more), lamps and door lintels, so walls, doors and
  // furniture a robot can collide with are kept and floor and ceiling are not.
  double band_min_m = 0.3;
  double band_max_m = 1.8;
};

}  // namespace fleetmerge
