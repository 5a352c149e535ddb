# rocking_sim and the core's GoogleTest suite (no ROS master needed).
# src/tools/rocking_sim*.cpp: main, the command line, the output, the ensemble (one job per file).
add_executable(rocking_sim src/tools/rocking_sim.cpp src/tools/rocking_sim_options.cpp
                           src/tools/rocking_sim_output.cpp src/tools/rocking_sim_ensemble.cpp
                           src/tools/rocking_sim_solid.cpp)
target_link_libraries(rocking_sim PRIVATE rocking_monitor_core CLI11::CLI11 nlohmann_json::nlohmann_json)
# its five files include CLI11 (header only): compiled as one unity source, CLI11 is compiled once
set_target_properties(rocking_sim PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${ROCKING_TOOL_DIR} UNITY_BUILD ON)

if(BUILD_TESTING)
  find_package(GTest REQUIRED)
  include(GoogleTest)
  # One executable for the core's suites; the sources mirror the layers (test/<layer>/).
  set(ROCKING_CORE_TESTS "")
  foreach(dir physics integrate model csv motion monitoring study feeds tools)
    file(GLOB tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/test/${dir}/*.cpp)
    list(APPEND ROCKING_CORE_TESTS ${tests})
  endforeach()
  # command-line tests with their own executables (they need rocking_study / ROS tools)
  list(FILTER ROCKING_CORE_TESTS EXCLUDE REGEX "/test_(study_cli|record_to_bag|record_to_mseed|progress_meter)\\.cpp$")
  # test/support/record_writers.cpp: the record-format writers (also the fuzzer's seeds, cmake/fuzz.cmake)
  add_executable(core_tests ${ROCKING_CORE_TESTS} ${CMAKE_CURRENT_SOURCE_DIR}/test/support/record_writers.cpp)
  target_link_libraries(core_tests PRIVATE rocking_monitor_core GTest::gtest_main
                        nlohmann_json::nlohmann_json)
  target_include_directories(core_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/test/support)
  target_compile_definitions(core_tests PRIVATE
    ROCKING_RECORDS_DIR="${ROCKING_RECORDS_DIR}"
    ROCKING_EXPERIMENTS_DIR="${ROCKING_EXPERIMENTS_DIR}"
    ROCKING_SIM_EXE="$<TARGET_FILE:rocking_sim>"
    ROCKING_EXPERIMENTS_EXE="$<TARGET_FILE:rocking_experiments>"
    ROCKING_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  add_dependencies(core_tests rocking_sim rocking_experiments)
  # Build time (issue 42 part 4, docs/performance.md 8f): the test files compile in unity batches of 8
  # (gtest, Eigen and the core's headers parsed once per batch, not per file; and at -O1 in Release,
  # CMakeLists.txt): 222 -> 89 CPU s. One batch is one translation unit: a name in a test file's
  # anonymous namespace must not repeat another test file's (the redefinition error names both).
  set_target_properties(core_tests PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  if(ROCKING_SANITIZE)
    target_compile_options(core_tests PRIVATE ${ROCKING_SANITIZE_FLAGS})
  endif()
  gtest_discover_tests(core_tests DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)
endif()
