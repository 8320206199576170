# The Debian package (scripts/package.sh): `cpack -G DEB` in a build configured with
# CMAKE_INSTALL_PREFIX=/usr makes fleetmerge_<version>_<arch>.deb with the command, the library,
# its header and CMake package (/usr/lib/<multiarch>/cmake/fleetmerge, found by find_package with
# no CMAKE_PREFIX_PATH) and the Python module (/usr/lib/python3/dist-packages/fleetmerge).
set(FLEETMERGE_CONTACT "fleetmerge maintainers <maintainers@users.noreply.h-seed-80730b71.example>")

# Debian's copyright file, machine-readable: the package's licence (SPDX Apache-2.0).
install(FILES ${CMAKE_CURRENT_LIST_DIR}/debian/copyright DESTINATION ${CMAKE_INSTALL_DOCDIR})
# The code linked statically into the binaries ships with its notices (the BSD licences ask a
# binary distribution to reproduce them): the Debian copyright file of each archive's package,
# as third-party/<package>.copyright (docs/licenses.md, "What the Debian package's binaries
# link").
foreach(package libceres-dev libopencv-core-dev liblz4-dev libzstd-dev libsqlite3-dev libbz2-dev)
  if(EXISTS /usr/share/doc/${package}/copyright)
    install(FILES /usr/share/doc/${package}/copyright
      DESTINATION ${CMAKE_INSTALL_DOCDIR}/third-party RENAME ${package}.copyright)
  endif()
endforeach()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME fleetmerge)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "${FLEETMERGE_CONTACT}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "merges the occupancy grid maps of a robot fleet (Hough-spectrum map merging)")
set(CPACK_PACKAGE_DESCRIPTION
  "fleetmerge merges the 2-D occupancy grid maps and OctoMap octrees of a fleet of robots, each in
its own frame, into one map (Carpin's Hough-spectrum method, Ceres refinement, a pose graph).
This package holds the fleetmerge command, libfleetmerge with its C++ header and CMake package,
and the fleetmerge Python 3 module.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # fleetmerge_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# Depends: the shared libraries the binaries link, with versions, from dpkg-shlibdeps; plus what
# the Python module needs at run time, which no ELF file says: the interpreter it was built for
# (the extension's ABI is python3.X's) and numpy (Map.data is a numpy array).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)  # shlibs for libfleetmerge; ldconfig: debian/postinst
if(FLEETMERGE_PYTHON_VERSION)  # python/CMakeLists.txt: the interpreter pybind11 built for
  string(REPLACE "." ";" major_minor ${FLEETMERGE_PYTHON_VERSION})
  list(GET major_minor 0 major)
  list(GET major_minor 1 minor)
  math(EXPR next_minor "${minor} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "python3 (>= ${major}.${minor}), python3 (<< ${major}.${next_minor}), python3-numpy")
endif()
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
  ${CMAKE_CURRENT_LIST_DIR}/debian/postinst ${CMAKE_CURRENT_LIST_DIR}/debian/prerm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
