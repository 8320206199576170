#include "cli/simulate_command.hpp"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <ostream>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "io/map_io.hpp"
#include "io/simulated_case_file.hpp"
#include "sim/simulation.hpp"

namespace fleetmerge {
namespace {

// Adds the building map's YAML and image to `inputs`: the case folder's files never overwrite them
// (a building map kept in the case folder under a robot's or the base's file name).
SimulationBuilding LoadBuilding(const std::filesystem::path& yaml, const std::string& name,
                                std::vector<std::filesystem::path>& inputs) {
  LoadedMap loaded = LoadMap(yaml);
  inputs.push_back(yaml);
  inputs.push_back(loaded.metadata.image_path);
  return {std::move(loaded.grid), name, yaml.string()};
}

void PrintCase(const SimulatedCase& simulated, const WrittenCase& written, double elapsed_ms,
               std::ostream& out) {
  out << std::fixed << std::setprecision(3);
  out << "simulated " << simulated.maps.size() << " robots in " << std::setprecision(0)
      << elapsed_ms << " ms" << std::setprecision(3) << "\n";
  if (simulated.base) {
    const OccupancyGrid& map = simulated.base->map;
    out << "  " << written.base_yaml.string() << ": building " << simulated.base->truth.building
        << ", its own map, " << map.width() << " x " << map.height() << " cells of "
        << simulated.base->truth.resolution_m << " m, fixed at the identity\n";
  }
  for (std::size_t k = 0; k < simulated.maps.size(); ++k) {
    const TruthMap& t = simulated.truth.maps[k];
    const OccupancyGrid& map = simulated.maps[k];
    out << "  " << written.map_yamls[k].string() << ": building " << t.building << ", "
        << map.width() << " x " << map.height() << " cells of " << t.resolution_m
        << " m, pose in building x " << t.T_building_map.x_m() << " m, y " << t.T_building_map.y_m()
        << " m, yaw " << t.T_building_map.yaw_rad() * 180.0 / M_PI << " deg";
    if (HasPrior(simulated.priors, static_cast<int>(k))) {
      const Pose2& T = simulated.priors[k]->T_site_map;
      out << "; initial_pose x " << T.x_m() << " m, y " << T.y_m() << " m, yaw "
          << T.yaw_rad() * 180.0 / M_PI << " deg";
    }
    out << "\n";
  }
  out << "true overlaps (building cells seen by both, share of the smaller map):\n";
  for (const TruthOverlap& o : WrittenTruth(simulated).overlaps) {
    out << "  " << o.a << " - " << o.b << ": " << o.cells << " cells, " << std::setprecision(2)
        << o.share << std::setprecision(3) << "\n";
  }
  out << "wrote " << written.truth_yaml.string() << " and " << written.job_yaml.string() << "\n"
      << "merge with: fleetmerge merge " << written.job_yaml.string() << "\n";
}

}  // namespace

CLI::App* AddSimulateCommand(CLI::App& app, SimulateCommand& c) {
  SimulationOptions& o = c.options;
  CLI::App* sim = app.add_subcommand(
      "simulate", "Write a multi-robot test case with a known answer (maps, truth.yaml, job.yaml)");
  sim->add_option("dir", c.out_dir, "output folder")->required();
  auto* building = sim->add_option("--building", c.building_yaml,
                                   "building map (map_server YAML) the robots explore");
  sim->add_option("--office-seed", c.office_seed,
                  "explore the synthetic office floor of this seed (default: --seed)")
      ->excludes(building);
  sim->add_option("--robots", o.robots, "robots in the building")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  sim->add_option("--seed", o.seed, "random seed of the whole case")->capture_default_str();
  sim->add_option("--beams", o.lidar.beams, "lidar beams over 360 degrees")
      ->check(CLI::Range(3, 100000))
      ->capture_default_str();
  sim->add_option("--range", o.lidar.range_m, "lidar maximum range, m")->capture_default_str();
  sim->add_option("--range-noise", o.lidar.range_noise_m, "std. dev. of range noise, m")
      ->capture_default_str();
  sim->add_option("--pose-noise", o.pose_noise.xy_m, "per-scan pose jitter (std. dev.), m")
      ->capture_default_str();
  sim->add_option("--pose-noise-yaw", o.pose_noise.yaw_deg, "per-scan yaw jitter, deg")
      ->capture_default_str();
  sim->add_option("--drift", o.pose_noise.drift_xy_m,
                  "position drift (random walk), std. dev. after 1 m of path, m")
      ->capture_default_str();
  sim->add_option("--drift-yaw", o.pose_noise.drift_yaw_deg,
                  "heading drift (random walk), std. dev. after 1 m of path, deg")
      ->capture_default_str();
  sim->add_option("--path-length", o.path_length_m, "exploration budget per robot, m")
      ->capture_default_str();
  sim->add_option("--clearance", o.clearance_m, "robot radius: distance kept from walls, m")
      ->capture_default_str();
  sim->add_option("--resolutions", o.resolutions_m,
                  "cell size of the robots' maps, m: one value, or one per robot (foreign last)")
      ->delimiter(',')
      ->check(CLI::Range(0.005, 1.0))
      ->capture_default_str();
  sim->add_flag("--fixed-base", o.fixed_base,
                "the building's own map joins the case as a fixed base map (base.yaml, first in "
                "job.yaml and truth.yaml), as in a site job");
  sim->add_option_function<std::vector<double>>(
         "--priors",
         [&o](const std::vector<double>& v) {
           if (v.size() != 2 && v.size() != 4) {
             throw CLI::ValidationError("--priors",
                                        "expected ERROR_M,ERROR_DEG or "
                                        "ERROR_M,ERROR_DEG,SIGMA_M,SIGMA_DEG");
           }
           o.priors = SimulationOptions::Priors{};
           o.priors->error_m = v[0];
           o.priors->error_deg = v[1];
           if (v.size() == 4) {
             o.priors->sigma_m = v[2];
             o.priors->sigma_deg = v[3];
           }
         },
         "each robot gets a known start pose (job.yaml's initial_pose) this far off its true "
         "pose: ERROR_M in a random direction and ERROR_DEG; sigmas SIGMA_M, SIGMA_DEG "
         "(default 0.5 m, 10 deg)")
      ->delimiter(',')
      ->expected(2, 4);
  sim->add_flag("--little-overlap", o.little_overlap,
                "robots start far apart and each explores only its own part of the building");
  auto* foreign = sim->add_option("--foreign", c.foreign_yaml,
                                  "add a robot that explored this other building (map YAML)");
  sim->add_option("--foreign-office-seed", c.foreign_office_seed,
                  "add a robot that explored the synthetic office of this seed")
      ->excludes(foreign);
  sim->add_option("--threads", o.threads, "robots simulated in parallel (0: all cores)")
      ->check(CLI::Range(0, 1024));
  return sim;
}

int RunSimulateCommand(const SimulateCommand& c, std::ostream& out) {
  ValidateSimulationOptions(c.options);  // before any map is read
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::filesystem::path> inputs;
  SimulationBuilding building;
  if (!c.building_yaml.empty()) {
    building = LoadBuilding(c.building_yaml, "building", inputs);
  } else {
    building = OfficeBuilding(c.office_seed.value_or(c.options.seed));
  }
  std::optional<SimulationBuilding> foreign;
  if (!c.foreign_yaml.empty()) {
    foreign = LoadBuilding(c.foreign_yaml, "foreign", inputs);
  } else if (c.foreign_office_seed) {
    if (c.building_yaml.empty() &&
        *c.foreign_office_seed == c.office_seed.value_or(c.options.seed)) {
      throw Error("--foreign-office-seed " + std::to_string(*c.foreign_office_seed) +
                  " is the building's own office seed: a foreign building must differ");
    }
    foreign = OfficeBuilding(*c.foreign_office_seed, "foreign");
  }
  const SimulatedCase simulated = SimulateFleet(building, c.options, foreign);
  const double elapsed_ms = MillisecondsSince(start);
  const WrittenCase written = WriteSimulatedCase(simulated, c.out_dir, inputs);
  PrintCase(simulated, written, elapsed_ms, out);
  return 0;
}

}  // namespace fleetmerge
