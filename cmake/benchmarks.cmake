# Benchmarks, accuracy/stability drivers and the independent CVODE cross-check of the reference
# integrator (issue 6). Included from the top CMakeLists.txt; every part is skipped with a notice
# when its dependency is missing, so the rest of the package still builds.
#
#   rocking_benchmarks   Google Benchmark: ns per item-step, real-time capacity at 200 Hz
#   monitor_benchmarks   Google Benchmark: the live monitor's core per input sample (10,000 two-plane items)
#   rocking_accuracy     work-precision, overturn agreement and stability-map CSVs (docs/performance)
#   reference_tests      gtest: dopri5 at tight tolerance against SUNDIALS CVODE (ctest)
#
# Benchmarks are only meaningful in an optimised build (Release is the default, see the top file).

if(CMAKE_BUILD_TYPE AND NOT CMAKE_BUILD_TYPE MATCHES "^(Release|RelWithDebInfo)$")
  message(WARNING "rocking_monitor: benchmarks built with CMAKE_BUILD_TYPE=${CMAKE_BUILD_TYPE}; "
                  "their timings are not representative (use Release)")
endif()

# ---------------------------------------------------------------- accuracy / stability driver
add_executable(rocking_accuracy bench/rocking_accuracy.cpp  # the CLI; one file per part in bench/accuracy/
               bench/accuracy/work_precision.cpp bench/accuracy/overturn_agreement.cpp
               bench/accuracy/stability_maps.cpp bench/accuracy/planar_vs_3d.cpp bench/accuracy/accuracy_policy.cpp)
target_include_directories(rocking_accuracy PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/bench ${CMAKE_CURRENT_SOURCE_DIR}/test/support
                           ${CMAKE_CURRENT_SOURCE_DIR}/src/tools)
target_link_libraries(rocking_accuracy PRIVATE rocking_monitor_core rocking_tool_progress CLI11::CLI11)
target_compile_definitions(rocking_accuracy PRIVATE ROCKING_RECORDS_DIR="${ROCKING_RECORDS_DIR}")
target_compile_options(rocking_accuracy PRIVATE -Wall -Wextra)
set_target_properties(rocking_accuracy PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${ROCKING_TOOL_DIR})

# ---------------------------------------------------------------- Google Benchmark
find_package(benchmark QUIET)
if(benchmark_FOUND)
  add_executable(rocking_benchmarks bench/rocking_benchmarks.cpp)
  target_include_directories(rocking_benchmarks PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/bench ${CMAKE_CURRENT_SOURCE_DIR}/test/support)
  target_link_libraries(rocking_benchmarks PRIVATE rocking_monitor_core benchmark::benchmark)
  target_compile_definitions(rocking_benchmarks PRIVATE ROCKING_RECORDS_DIR="${ROCKING_RECORDS_DIR}")
  target_compile_options(rocking_benchmarks PRIVATE -Wall -Wextra)
  set_target_properties(rocking_benchmarks PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${ROCKING_TOOL_DIR})

  add_executable(monitor_benchmarks bench/monitor_benchmarks.cpp)
  target_include_directories(monitor_benchmarks PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/bench ${CMAKE_CURRENT_SOURCE_DIR}/test/support)
  find_package(TBB REQUIRED)
  target_link_libraries(monitor_benchmarks PRIVATE rocking_monitor_core benchmark::benchmark TBB::tbb)
  target_compile_definitions(monitor_benchmarks PRIVATE ROCKING_RECORDS_DIR="${ROCKING_RECORDS_DIR}"
                             ROCKING_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  target_compile_options(monitor_benchmarks PRIVATE -Wall -Wextra)
  set_target_properties(monitor_benchmarks PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${ROCKING_TOOL_DIR})
else()
  message(STATUS "rocking_monitor: Google Benchmark not found (libbenchmark-dev): "
                 "rocking_benchmarks not built")
endif()

# ---------------------------------------------------------------- CVODE reference tests
if(BUILD_TESTING)
  # Debian 12 ships SUNDIALS 6.4 with a CMake package; fall back to the plain libraries.
  set(ROCKING_CVODE_LIBS "")
  find_package(SUNDIALS CONFIG QUIET)
  if(TARGET SUNDIALS::cvode_shared AND TARGET SUNDIALS::nvecserial_shared)
    set(ROCKING_CVODE_LIBS SUNDIALS::cvode_shared SUNDIALS::nvecserial_shared)
    if(TARGET SUNDIALS::sunlinsoldense_shared AND TARGET SUNDIALS::sunmatrixdense_shared)
      list(APPEND ROCKING_CVODE_LIBS SUNDIALS::sunlinsoldense_shared SUNDIALS::sunmatrixdense_shared)
    endif()
  else()
    find_path(ROCKING_CVODE_INCLUDE cvode/cvode.h)
    find_library(ROCKING_CVODE_LIB sundials_cvode)
    find_library(ROCKING_NVECSERIAL_LIB sundials_nvecserial)
    find_library(ROCKING_SUNLINSOLDENSE_LIB sundials_sunlinsoldense)
    find_library(ROCKING_SUNMATRIXDENSE_LIB sundials_sunmatrixdense)
    if(ROCKING_CVODE_INCLUDE AND ROCKING_CVODE_LIB AND ROCKING_NVECSERIAL_LIB)
      set(ROCKING_CVODE_LIBS ${ROCKING_CVODE_LIB} ${ROCKING_NVECSERIAL_LIB})
      if(ROCKING_SUNLINSOLDENSE_LIB AND ROCKING_SUNMATRIXDENSE_LIB)
        list(APPEND ROCKING_CVODE_LIBS ${ROCKING_SUNLINSOLDENSE_LIB} ${ROCKING_SUNMATRIXDENSE_LIB})
      endif()
    endif()
  endif()
  if(ROCKING_CVODE_LIBS)
    find_package(GTest REQUIRED)
    include(GoogleTest)
    add_executable(reference_tests test/reference/test_cvode_reference.cpp)
    target_include_directories(reference_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/bench ${CMAKE_CURRENT_SOURCE_DIR}/test/support)
    if(ROCKING_CVODE_INCLUDE)
      target_include_directories(reference_tests PRIVATE ${ROCKING_CVODE_INCLUDE})
    endif()
    target_link_libraries(reference_tests PRIVATE rocking_monitor_core GTest::gtest_main
                          ${ROCKING_CVODE_LIBS})
    target_compile_definitions(reference_tests PRIVATE ROCKING_RECORDS_DIR="${ROCKING_RECORDS_DIR}")
    target_compile_options(reference_tests PRIVATE -Wall -Wextra)
    gtest_discover_tests(reference_tests TEST_PREFIX "reference." DISCOVERY_TIMEOUT 60
                         PROPERTIES TIMEOUT 600)
  else()
    message(STATUS "rocking_monitor: SUNDIALS CVODE not found (libsundials-dev): "
                   "reference_tests not built")
  endif()
endif()

# ---------------------------------------------------------------- Bullet 3-D reference tests
# reference_3d_tests: Rocking3DModel against Bullet Physics (test/reference/bullet_rocking.*),
# Debian's double-precision build (libbullet-dev: pkg-config bullet-float64).
if(BUILD_TESTING)
  find_package(PkgConfig QUIET)
  if(PkgConfig_FOUND)
    pkg_check_modules(ROCKING_BULLET QUIET IMPORTED_TARGET bullet-float64)
  endif()
  if(ROCKING_BULLET_FOUND)
    find_package(GTest REQUIRED)
    find_package(ZLIB REQUIRED)
    include(GoogleTest)
    add_executable(reference_3d_tests test/reference/test_bullet_reference.cpp test/reference/test_bullet_granite.cpp
                   test/reference/bullet_rocking.cpp)
    target_include_directories(reference_3d_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/test/reference)
    target_link_libraries(reference_3d_tests PRIVATE rocking_monitor_core GTest::gtest_main
                          PkgConfig::ROCKING_BULLET ZLIB::ZLIB nlohmann_json::nlohmann_json)
    # The granite case runs scripts/rocking_geometry.py (numpy, scipy) for the specimens' geometry.
    set(ROCKING_BULLET_PYTHON "${PYTHON_EXECUTABLE}")
    if(NOT ROCKING_BULLET_PYTHON)
      set(ROCKING_BULLET_PYTHON python3)
    endif()
    target_compile_definitions(reference_3d_tests PRIVATE
                               ROCKING_EXPERIMENTS_DIR="${ROCKING_EXPERIMENTS_DIR}"
                               ROCKING_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}"
                               ROCKING_PYTHON="${ROCKING_BULLET_PYTHON}")
    target_compile_options(reference_3d_tests PRIVATE -Wall -Wextra)
    gtest_discover_tests(reference_3d_tests TEST_PREFIX "reference3d." DISCOVERY_TIMEOUT 60
                         PROPERTIES TIMEOUT 600)
  else()
    message(STATUS "rocking_monitor: Bullet not found (libbullet-dev, pkg-config bullet-float64): "
                   "reference_3d_tests not built")
  endif()
endif()
