# Read by packages that find rocking_monitor (catkin CFG_EXTRAS; devel and install space): the core's
# static libraries need what they were linked with, found as cmake/layers.cmake finds it, after them
# on the link line; their headers need Eigen.
find_package(Eigen3 REQUIRED NO_MODULE)
find_package(PkgConfig REQUIRED)
pkg_check_modules(ROCKING_MONITOR_HWY REQUIRED libhwy)
pkg_check_modules(ROCKING_MONITOR_MSEED REQUIRED mseed)
find_library(ROCKING_MONITOR_LIBCSV csv)
if(NOT ROCKING_MONITOR_LIBCSV)
  message(FATAL_ERROR "rocking_monitor needs libcsv: apt-get install libcsv-dev")
endif()
find_package(yaml-cpp REQUIRED)
find_package(ZLIB REQUIRED)
find_package(Threads REQUIRED)
list(APPEND rocking_monitor_INCLUDE_DIRS ${EIGEN3_INCLUDE_DIRS})
list(APPEND rocking_monitor_LIBRARIES ${ROCKING_MONITOR_HWY_LINK_LIBRARIES} ${ROCKING_MONITOR_MSEED_LINK_LIBRARIES}
     ${ROCKING_MONITOR_LIBCSV} ${YAML_CPP_LIBRARIES} ZLIB::ZLIB Threads::Threads)
