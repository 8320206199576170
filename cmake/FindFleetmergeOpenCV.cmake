# Finds the three OpenCV modules fleetmerge uses (core, imgproc, imgcodecs) and defines the
# imported targets opencv_core, opencv_imgproc, opencv_imgcodecs.
#
# Why not find_package(OpenCV): on Debian the CMake config ships only in libopencv-dev, which
# pulls ~150 packages (GUI, video, contrib). The per-module -dev packages have headers and
# libraries but no config, so we locate them here.
find_path(FleetmergeOpenCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
set(_fm_opencv_vars FleetmergeOpenCV_INCLUDE_DIR)
foreach(module core imgproc imgcodecs)
  find_library(FleetmergeOpenCV_${module}_LIBRARY opencv_${module})
  list(APPEND _fm_opencv_vars FleetmergeOpenCV_${module}_LIBRARY)
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(FleetmergeOpenCV REQUIRED_VARS ${_fm_opencv_vars})

if(FleetmergeOpenCV_FOUND)
  foreach(module core imgproc imgcodecs)
    if(NOT TARGET opencv_${module})
      add_library(opencv_${module} UNKNOWN IMPORTED)
      set_target_properties(opencv_${module} PROPERTIES
        IMPORTED_LOCATION "${FleetmergeOpenCV_${module}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${FleetmergeOpenCV_INCLUDE_DIR}")
    endif()
  endforeach()
  set_property(TARGET opencv_imgproc APPEND PROPERTY INTERFACE_LINK_LIBRARIES opencv_core)
  set_property(TARGET opencv_imgcodecs APPEND PROPERTY INTERFACE_LINK_LIBRARIES opencv_core)
endif()
