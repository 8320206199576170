#!/usr/bin/env bash
# CI stage: the whole test suite built with AddressSanitizer + UndefinedBehaviorSanitizer (clang,
# -O1, no benchmarks; scripts/sanitize_build.sh) in build-fuzz/. Any sanitizer report fails its
# test (no recovery). The heavy accuracy tests run a reduced number of trials
# (FLEETMERGE_TEST_SCALE), and the real-map accuracy sweeps run on the Intel map only: the other
# buildings repeat the same code paths on more data (they run in full in scripts/test.sh), and
# under ASan they took 300 s of CPU, which CI's 25 minutes cannot spare. Likewise three tests
# that rerun covered code with other settings (70 s of CPU), and the check of the executable's
# shared libraries, which holds for the file-by-file build only.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
bash scripts/sanitize_build.sh
# detect_leaks: OpenCV's and Ceres's process-lifetime singletons are not leaks we can fix, but
# our own are: leak checking stays on. halt_on_error: the first report fails the test.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:abort_on_error=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export FLEETMERGE_TEST_SCALE="${FLEETMERGE_TEST_SCALE:-0.06}"
same_paths_on_more_data='^RealMaps/PairAccuracy\..*/(willow|aces3|mit_csail|gdc|stata)'
same_paths_on_more_data+='|^RealMaps/FleetAccuracy\..*/(willo|aces3)'
same_paths_on_more_data+='|^FleetMerge\.ForeignMapStaysUnmerged|^OmegaMargin\.'
same_paths_on_more_data+='|^FleetAccuracySuite\.KnownHardBuilding|^PairAccuracy\.DifferentResolutions'
# Same code as other tests, run again with other settings (threads, sampling, kills).
same_paths_on_more_data+='|^FleetMerge\.ResultDoesNotDependOnThreadCount'
same_paths_on_more_data+='|^PairAccuracy\.SampledTranslationPoints|^MergeKillTest\.'
# The ranking on more simulated fleets (pose_evidence_test covers its code), and fixed maps that
# disagree (RobotsInARealBuildingLandOnItsFixedMap covers the fixed path).
same_paths_on_more_data+='|^LookAlikeRanking\.|^FixedBase\.SeveralFixedMapsNeverMove'
# Fixed bases in Willow, MIT CSAIL and the Nav2 warehouse: the fixed maps' search penalty runs in
# RobotsInARealBuildingLandOnItsFixedMap, the weak-bridge exemption, the weak-edge rule and the
# cells of a split in weak_bridges_test, pose_graph_test and corroboration_test (about 60 s of
# CPU under ASan).
same_paths_on_more_data+='|^FixedBase\.(PairsWithAPorous|RobotsOnAPorous|ARobotRightOnTheSiteMap)'
# Robots in a site of four buildings (16 M cells): the pooling and the search from the smaller map
# that these test run in pairs of any size (translation_search_test, pair_accuracy_test,
# prepared_map_test); each simulation alone takes 5-7 s.
same_paths_on_more_data+='|^FixedBase\.[A-Za-z]*SiteOfFourBuildings'
# Known start poses: AWrongPriorGetsItsPairRefusedWithAReason runs the refusal, the prior edges and
# the site-frame node; Api.AMapThatPairsWithNoneIsPlacedAtItsInitialPose the placement by a prior.
# The other three rerun that code on more robots (about 65 s of CPU under ASan).
same_paths_on_more_data+='|^Priors\.(SlightlyOff|WithoutAFixedMap|ARobotThatOverlapsNobody)'
# The only map with a prior placed alone: MergeCliTest.TheOnlyMapWithAStartPoseIsPlacedAtItAlone
# runs that placement and its merged map on small maps; the Priors test reruns it on 5 simulated
# robots (about 17 s under ASan).
same_paths_on_more_data+='|^Priors\.TheOnlyMapWithAPriorIsPlacedByItAlone'
# report.html in Chromium: what it checks is the page's script, which no sanitizer sees; the
# merges that write its result sets (four_robots, site_with_priors, a pair, octrees) run in the
# CLI, report and octree tests here (about 41 s under ASan).
same_paths_on_more_data+='|^report_browser_test$'
# Command lines and output streams, not memory: CliTest.UsageErrorsExitTwo starts the executable
# 14 times (exit codes) and MergeCliOctrees.QuietMergeOfOctreesPrintsNothingOnStderr checks
# stderr (the octree merge runs in OctreeFleet.*); the cache's size bound on 276 pairs
# (PairCacheTest.ABoundBelowTheJobsPairsKeepsThemAll runs it on 3). About 60 s of CPU under ASan.
same_paths_on_more_data+='|^CliTest\.UsageErrorsExitTwo|^MergeCliOctrees\.QuietMergeOfOctrees'
same_paths_on_more_data+='|^MergeCacheCliTest\.ABoundBelowTheJobsPairsKeepsThemAndWarns'
# The local refinement at three tolerances on 5 robots in MIT CSAIL (every pair's refinement
# runs here at the default one), one pair's hypotheses on several threads (`pair` runs a pair on
# all cores in cli_test here; FleetMerge.ResultDoesNotDependOnThreadCount is left out likewise),
# and three command-line checks whose code runs in the unit tests here: the fixed-base case
# (simulation_test, simulation_file_test, fixed_base_test), the building map's protected files
# (atomic_file_test, map_io_test) and the map-list options refused with job files (an error
# before any work). About 42 s of CPU under ASan; CI's last run took 1458 s of its 25 minutes.
same_paths_on_more_data+='|^LocalAlignment\.TighterToleranceEndsNearerTheMinimum'
same_paths_on_more_data+='|^PreparedMapTest\.OnePairOnSeveralThreadsGivesTheOneThreadHypotheses'
same_paths_on_more_data+='|^SimulateCli\.(AFixedBaseCaseIsEvaluated|CaseCommandsNeverOverwrite)'
same_paths_on_more_data+='|^MergeCliTest\.MapListOptionsAndAnEmptyBand'
# The executable's own shared libraries (cli/CMakeLists.txt): a unity build's executable links
# whole batches of files, and so what any file of a batch calls (Ceres, LAPACK, OctoMap); stage 1
# checks the file-by-file build that users get.
same_paths_on_more_data+='|^CliExecutable\.HoldsItsOwnOpenCvCoreAndExportsNoneOfIt'
ctest --test-dir build-fuzz --output-on-failure -j"$jobs" -E "$same_paths_on_more_data"
