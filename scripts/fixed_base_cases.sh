# Sourced by the fixed-base scripts: the whole real buildings in ../shared/data/maps. Not the
# partial runs of one floor (robotis_corridor_run*, lab_pair_demo_*), not the same building twice
# (intel_lab_10cm_grey, willow-full-0.10), not the 4 x 4 m maze arena (smaller than
# min_overlap_cells: nothing in it can be merged with the defaults).
# shellcheck disable=SC2034  # used by the scripts that source this file
whole_buildings="aces3_austin bookstore_tb3 gdc_floor1_full gdc_floor2_full intel_lab
  mit_building_31 mit_csail nav2_depot nav2_warehouse office_raw_rplidarA3 stata_basement
  turtlebot3_world_sim warehouse_002 willow-full-0.05"
