# Sourced by scripts/fixed_base_accuracy.sh and scripts/fixed_base_penalty.sh (from the
# repository root): robots simulated in the whole real buildings of ../shared/data/maps, merged
# or paired with the building's own map.
# Usage: source scripts/fixed_base_cases.sh SCRIPT_NAME OUT_DIR
# Sets what scripts/simulated_cases.sh sets (fleetmerge, maps, out), and buildings and seeds
# (FIXED_BASE_SEEDS, default 1 to 10). The buildings are not the partial runs of one floor
# (robotis_corridor_run*, lab_pair_demo_*), not the same building twice (intel_lab_10cm_grey,
# willow-full-0.10), not the 4 x 4 m maze arena (smaller than min_overlap_cells: nothing in it
# can be merged with the defaults).
# shellcheck disable=SC2034  # used by the scripts that source this file
source scripts/simulated_cases.sh "$1" "$2"
buildings="aces3_austin bookstore_tb3 gdc_floor1_full gdc_floor2_full intel_lab mit_building_31
  mit_csail nav2_depot nav2_warehouse office_raw_rplidarA3 stata_basement turtlebot3_world_sim
  warehouse_002 willow-full-0.05"
seeds=${FIXED_BASE_SEEDS:-1 2 3 4 5 6 7 8 9 10}
