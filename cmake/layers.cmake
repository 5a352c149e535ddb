# The ROS-free core as one static library per layer (folder), linked in one direction only.
#
#   layer        folder (src/, include/rocking_monitor/)   may include / link
#   physics      physics/      the paper's equations     constants.hpp
#   integrate    integrate/    steppers, event location  physics
#   model        model/        rocking, contact, adaptive integrate, physics
#   csv          csv/          CSV reading and writing   (nothing)
#   motion       motion/       ground motion, records    csv
#   monitoring   monitoring/   per-item monitor, offline model, motion and below
#   study        study/        the paper's study         monitoring (catalogue items, ensembles) and below
#   feeds        feeds/        live instrument streams   (nothing)
#   notify       notify/       alarm notifier's core     monitoring (AlarmDedup) and below
#
include(${CMAKE_CURRENT_LIST_DIR}/layers_rules.cmake)  # who may include whom

# scripts/run_sanitizers.sh: AddressSanitizer + UndefinedBehaviorSanitizer on the core layers, core_tests
# and the fuzz driver only (test/fuzz/, cmake/fuzz.cmake); a separate build directory, never Release.
option(ROCKING_SANITIZE "Build the core, core_tests and fuzz drivers with -fsanitize=address,undefined" OFF)
set(ROCKING_SANITIZE_FLAGS -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)

# g and pi, shared by every layer (header only).
add_library(rocking_monitor_constants INTERFACE)
target_include_directories(rocking_monitor_constants INTERFACE
  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>)

# Runs on every build before any core source compiles: a wrong-way include stops the build.
add_custom_target(check_layers ALL
  COMMAND ${CMAKE_COMMAND} -DROOT=${CMAKE_CURRENT_SOURCE_DIR} -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/check_layers.cmake
  COMMENT "Checking the core's layering (cmake/layers.cmake)"
  VERBATIM)

foreach(layer ${ROCKING_CORE_LAYER_NAMES})
  set(target rocking_monitor_${layer})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/${layer}/*.cpp)
  add_library(${target} STATIC ${sources})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>)
  target_link_libraries(${target} PUBLIC rocking_monitor_constants Eigen3::Eigen)
  foreach(below ${ROCKING_LAYER_ALLOWS_${layer}})
    target_link_libraries(${target} PUBLIC rocking_monitor_${below})
  endforeach()
  # -fno-math-errno: nothing reads errno after sin/cos/sqrt, and with it GCC may merge repeated
  # sin/cos of one angle and inline sqrt (same IEEE results; the bit-for-bit tests hold):
  # monitor_benchmarks batch 4.02/3.84 -> 3.80/3.62 ms per sample, alternating runs.
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -fno-math-errno)
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  add_dependencies(${target} check_layers)
  if(ROCKING_SANITIZE)
    target_compile_options(${target} PRIVATE ${ROCKING_SANITIZE_FLAGS})
    target_link_options(${target} PUBLIC ${ROCKING_SANITIZE_FLAGS})  # whoever links a sanitized layer
  endif()
endforeach()

# CSV is parsed by libcsv (Debian libcsv-dev: csv.h, libcsv.so).
find_path(ROCKING_LIBCSV_INCLUDE csv.h)
find_library(ROCKING_LIBCSV csv)
if(NOT ROCKING_LIBCSV_INCLUDE OR NOT ROCKING_LIBCSV)
  message(FATAL_ERROR "libcsv not found: apt-get install libcsv-dev (scripts/install_deps.sh)")
endif()
target_include_directories(rocking_monitor_csv PRIVATE ${ROCKING_LIBCSV_INCLUDE})
target_link_libraries(rocking_monitor_csv PRIVATE ${ROCKING_LIBCSV})

# The batch engine's SIMD (model/batch_rocking*.cpp): Highway (Debian libhwy-dev), one copy of
# the kernels per instruction set, chosen at run time. HWY_TARGET_INCLUDE names the kernel file
# relative to the package root. No fused multiply-add in the kernels: each lane must give the
# scalar model's bits (the scalar core is compiled for baseline x86-64, which has no FMA).
find_package(PkgConfig REQUIRED)
pkg_check_modules(ROCKING_HWY REQUIRED IMPORTED_TARGET libhwy)
target_link_libraries(rocking_monitor_model PUBLIC PkgConfig::ROCKING_HWY)
target_include_directories(rocking_monitor_model PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
# Highway re-includes this file once per instruction set (HWY_TARGET_INCLUDE): never merged into a
# unity source (scripts/run_sanitizers.sh builds with CMAKE_UNITY_BUILD).
set_source_files_properties(${CMAKE_CURRENT_SOURCE_DIR}/src/model/batch_rocking_simd.cpp
  PROPERTIES COMPILE_OPTIONS "-ffp-contract=off" SKIP_UNITY_BUILD_INCLUSION ON)
if(ROCKING_SANITIZE)
  # Under the sanitizers this one file took 160 of the tree's CPU seconds: Highway compiles its kernels
  # once per target (SCALAR, SSSE3, SSE4, AVX2, AVX3). SSSE3 is 128-bit like SSE4, 2 doubles a vector,
  # so the loads and stores ASan checks keep every width the machine can run (1, 2, 4, and 8 on
  # AVX-512) without it; AVX3 only where the CPU has AVX-512 (it cannot run elsewhere). The Release
  # build keeps all five and BatchRocking.EverySimdTargetGivesTheSameBits checks each one's bits
  # there. PUBLIC: the test must see the same list of compiled targets as the kernels.
  set(_hwy_off "HWY_SSSE3")
  if(EXISTS /proc/cpuinfo)
    file(STRINGS /proc/cpuinfo _avx512 REGEX "^flags.* avx512f" LIMIT_COUNT 1)
    if(NOT _avx512)
      string(APPEND _hwy_off "|HWY_AVX3")
    endif()
  endif()
  target_compile_definitions(rocking_monitor_model PUBLIC "HWY_DISABLED_TARGETS=(${_hwy_off})")
endif()

# miniSEED records are decoded by libmseed 2 (Debian libmseed-dev, pkg-config `mseed`).
pkg_check_modules(ROCKING_MSEED REQUIRED IMPORTED_TARGET mseed)
target_link_libraries(rocking_monitor_motion PRIVATE PkgConfig::ROCKING_MSEED)

# The catalogue (monitoring/catalogue*.cpp) is parsed from JSON values (its header names
# nlohmann::json) and read from YAML files; the study runs its cases on std::thread workers and reads
# YAML bodies / writes a JSON summary.
find_package(yaml-cpp REQUIRED)
target_link_libraries(rocking_monitor_monitoring PUBLIC nlohmann_json::nlohmann_json)
target_link_libraries(rocking_monitor_study PUBLIC Threads::Threads PRIVATE nlohmann_json::nlohmann_json)
# The shaking-table experiments (study/shaking_table_experiments.cpp) read gzipped CSV with zlib;
# the state snapshots (monitoring/state_snapshot.cpp) are checksummed with its CRC-32 and written on a
# thread of their own (monitoring/snapshot_file_writer.cpp); their payload's layout is the private
# header src/monitoring/state_snapshot_fields.hpp.
find_package(ZLIB REQUIRED)
target_link_libraries(rocking_monitor_study PRIVATE ZLIB::ZLIB)
target_link_libraries(rocking_monitor_monitoring PRIVATE ZLIB::ZLIB Threads::Threads)
# Debian's yaml-cpp 0.7 exports the plain target name `yaml-cpp` (later versions: yaml-cpp::yaml-cpp).
foreach(target rocking_monitor_monitoring rocking_monitor_study)
  if(TARGET yaml-cpp::yaml-cpp)
    target_link_libraries(${target} PRIVATE yaml-cpp::yaml-cpp)
  else()
    target_link_libraries(${target} PRIVATE yaml-cpp)
  endif()
endforeach()

# Umbrella: the whole core, for tools, tests and the ROS layer.
add_library(rocking_monitor_core INTERFACE)
foreach(layer ${ROCKING_CORE_LAYER_NAMES})
  # notify (libcurl, libmosquitto) only where it is used: the notifier and its tests.
  if(NOT layer STREQUAL "notify")
    target_link_libraries(rocking_monitor_core INTERFACE rocking_monitor_${layer})
  endif()
endforeach()
target_link_libraries(rocking_monitor_core INTERFACE Threads::Threads)

# --- feeds (issue 18): its third-party libraries and gtests.
include(${CMAKE_CURRENT_LIST_DIR}/feeds.cmake)
# --- notify (issue 44): libcurl, libmosquitto, yaml-cpp; its gtests (notify_tests).
include(${CMAKE_CURRENT_LIST_DIR}/notify.cmake)
