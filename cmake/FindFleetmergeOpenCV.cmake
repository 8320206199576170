# Finds the OpenCV modules fleetmerge uses and defines their imported targets: opencv_core and
# opencv_imgproc (required), opencv_imgcodecs when found (only three tests use it, as an
# independent PNG decoder; Debian's libopencv-imgcodecs-dev pulls GDAL, which the command's
# quick start does without), and opencv_core_static when OpenCV core's static archive is there
# (libopencv-core-dev ships it, with the TBB and zlib it needs): the `fleetmerge` executable
# links it (core/CMakeLists.txt).
#
# Why not find_package(OpenCV): on Debian the CMake config ships only in libopencv-dev, which
# pulls ~150 packages (GUI, video, contrib). The per-module -dev packages have headers and
# libraries but no config, so we locate them here.
find_path(FleetmergeOpenCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
set(_fm_opencv_vars FleetmergeOpenCV_INCLUDE_DIR)
foreach(module core imgproc)
  find_library(FleetmergeOpenCV_${module}_LIBRARY opencv_${module})
  list(APPEND _fm_opencv_vars FleetmergeOpenCV_${module}_LIBRARY)
endforeach()
find_library(FleetmergeOpenCV_imgcodecs_LIBRARY opencv_imgcodecs)
find_library(FleetmergeOpenCV_core_STATIC_LIBRARY libopencv_core.a)
find_library(FleetmergeOpenCV_tbb_LIBRARY tbb)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(FleetmergeOpenCV REQUIRED_VARS ${_fm_opencv_vars})

if(FleetmergeOpenCV_FOUND)
  foreach(module core imgproc imgcodecs)
    if(NOT FleetmergeOpenCV_${module}_LIBRARY)
      continue()
    endif()
    if(NOT TARGET opencv_${module})
      add_library(opencv_${module} UNKNOWN IMPORTED)
      set_target_properties(opencv_${module} PROPERTIES
        IMPORTED_LOCATION "${FleetmergeOpenCV_${module}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${FleetmergeOpenCV_INCLUDE_DIR}")
    endif()
  endforeach()
  set_property(TARGET opencv_imgproc APPEND PROPERTY INTERFACE_LINK_LIBRARIES opencv_core)
  if(FleetmergeOpenCV_core_STATIC_LIBRARY AND FleetmergeOpenCV_tbb_LIBRARY
     AND NOT TARGET opencv_core_static)
    add_library(opencv_core_static STATIC IMPORTED)
    set_target_properties(opencv_core_static PROPERTIES
      IMPORTED_LOCATION "${FleetmergeOpenCV_core_STATIC_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${FleetmergeOpenCV_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${FleetmergeOpenCV_tbb_LIBRARY};ZLIB::ZLIB;${CMAKE_DL_LIBS}")
  endif()
  if(TARGET opencv_imgcodecs)
    set_property(TARGET opencv_imgcodecs APPEND PROPERTY INTERFACE_LINK_LIBRARIES opencv_core)
  endif()
endif()
