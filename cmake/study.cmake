# rocking_study: the paper's study over every record (issue 5). Included by the top CMakeLists.
#
# The ROS-free study logic is the core layer rocking_monitor_study (src/study/, cmake/layers.cmake).

# src/tools/rocking_study.cpp parses the flags and runs one job; the parts, one job per file: the
# flags, the inputs, the study, --fragility, --merge, writing a file.
# The long tools' progress display (done / total, rate, time left; on a terminal only): rocking_study,
# rocking_experiments and rocking_accuracy link it.
add_library(rocking_tool_progress STATIC src/tools/progress_meter.cpp)
target_compile_options(rocking_tool_progress PRIVATE -Wall -Wextra -Wpedantic)
target_include_directories(rocking_tool_progress PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/src/tools)

add_executable(rocking_study
  src/tools/rocking_study.cpp src/tools/study_options.cpp src/tools/study_inputs.cpp
  src/tools/study_cases_job.cpp src/tools/study_fragility_job.cpp src/tools/study_merge_job.cpp
  src/tools/study_output_files.cpp)
target_link_libraries(rocking_study PRIVATE rocking_monitor_core rocking_tool_progress CLI11::CLI11)
target_compile_definitions(rocking_study PRIVATE ROCKING_RECORDS_DIR="${ROCKING_RECORDS_DIR}")
target_compile_options(rocking_study PRIVATE -Wall -Wextra -Wpedantic)
# compiled as one unity source, so CLI11 (header only) and the core's headers are compiled once
set_target_properties(rocking_study PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${ROCKING_TOOL_DIR} UNITY_BUILD ON)

if(BUILD_TESTING)
  # test/study/test_study*.cpp are globbed into core_tests; they also exercise the YAML/JSON part.
  # The command-line tests need the rocking_study binary: a separate target with its path.
  find_package(GTest REQUIRED)
  include(GoogleTest)
  add_executable(study_cli_tests ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/test_study_cli.cpp)
  target_link_libraries(study_cli_tests PRIVATE rocking_monitor_core GTest::gtest_main
                        nlohmann_json::nlohmann_json)
  target_compile_definitions(study_cli_tests PRIVATE
    ROCKING_RECORDS_DIR="${ROCKING_RECORDS_DIR}"
    ROCKING_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}"
    ROCKING_STUDY_EXE="$<TARGET_FILE:rocking_study>"
    ROCKING_PYTHON="/usr/bin/python3")
  target_include_directories(study_cli_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/test/support)
  add_dependencies(study_cli_tests rocking_study)
  gtest_discover_tests(study_cli_tests DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 900)
  # The progress display's line and when it draws (test/tools/test_progress_meter.cpp); the tools'
  # own output off a terminal, on a pseudo-terminal and with --quiet: test/tools/progress_only_on_a_terminal.sh.
  add_executable(progress_meter_tests ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/test_progress_meter.cpp)
  target_link_libraries(progress_meter_tests PRIVATE rocking_tool_progress GTest::gtest_main)
  gtest_discover_tests(progress_meter_tests DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 60)
endif()

# rocking_experiments: the real shaking-table experiments (issue 20, docs/validation.md).
# src/tools/rocking_experiments.cpp parses the flags and runs one job; the parts, one job per file:
# the flags, the shared setup, specimens, histories, predicting and scoring, margins.
add_executable(rocking_experiments
  src/tools/rocking_experiments.cpp src/tools/experiments_options.cpp
  src/tools/experiment_run.cpp src/tools/experiment_specimens.cpp
  src/tools/experiment_histories.cpp src/tools/experiment_predictions.cpp
  src/tools/experiment_scores.cpp src/tools/experiment_margins.cpp)
target_link_libraries(rocking_experiments PRIVATE rocking_monitor_core rocking_tool_progress CLI11::CLI11)
target_compile_options(rocking_experiments PRIVATE -Wall -Wextra -Wpedantic)
# compiled as one unity source, so CLI11 (header only) and the core's headers are compiled once
set_target_properties(rocking_experiments PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${ROCKING_TOOL_DIR} UNITY_BUILD ON)

if(BUILD_TESTING)
  # rocking_geometry.py (issue 20) on closed forms: box, off-centre hollow, box turned about z; the
  # entry's 3-D keys (base polygon CCW, centre of mass, inertia) and --com-shift.
  add_test(NAME rocking_geometry_closed_forms
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/test_rocking_geometry.py)
  set_tests_properties(rocking_geometry_closed_forms PROPERTIES TIMEOUT 60)
  # calibrate_experiments.py: the fit recovers a known grid point and noise from synthetic data, CV
  # never sees a held-out outcome; the pipeline on box meshes with a stub rocking_experiments.
  add_test(NAME calibrate_experiments_synthetic
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/test_calibrate_experiments.py)
  set_tests_properties(calibrate_experiments_synthetic PROPERTIES TIMEOUT 120)
  # fragility_experiments.py (issue 41): overturn intervals, the lognormal's closed form, a known
  # (mu, beta) recovered, CV blind to held-out outcomes, the pipeline with a stand-in tool.
  add_test(NAME fragility_experiments_synthetic
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/test_fragility_experiments.py)
  set_tests_properties(fragility_experiments_synthetic PROPERTIES TIMEOUT 120)
  # scripts/progress_bar.py (issue 53): the scripts' tqdm bar only on a terminal (a pseudo-terminal
  # here), never off one, none with --quiet.
  add_test(NAME scripts.progress_bar_only_on_a_terminal
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/test_progress_bar.py)
  set_tests_properties(scripts.progress_bar_only_on_a_terminal PROPERTIES TIMEOUT 60)
endif()

if(BUILD_TESTING)
  add_test(NAME rocking_experiments_accounting
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/experiments_accounting.sh
                   $<TARGET_FILE:rocking_experiments> ${ROCKING_EXPERIMENTS_DIR}/granite_pbr
                   ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/granite_specimens.yaml)
  set_tests_properties(rocking_experiments_accounting PROPERTIES TIMEOUT 60 SKIP_RETURN_CODE 77)
  add_test(NAME rocking_experiments_histories
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/experiments_histories.sh
                   $<TARGET_FILE:rocking_experiments> ${ROCKING_EXPERIMENTS_DIR}/granite_pbr
                   ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/granite_specimens.yaml)
  set_tests_properties(rocking_experiments_histories PROPERTIES TIMEOUT 60 SKIP_RETURN_CODE 77)
  # The same accounting through the 3-D model (the catalogue's base polygons: --model auto picks it).
  add_test(NAME rocking_experiments_histories_3d
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/experiments_histories.sh
                   $<TARGET_FILE:rocking_experiments> ${ROCKING_EXPERIMENTS_DIR}/granite_pbr
                   ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/granite_specimens_3d.yaml)
  set_tests_properties(rocking_experiments_histories_3d PROPERTIES TIMEOUT 60 SKIP_RETURN_CODE 77)
  # A specimen's catalogue yaw is the table azimuth with the opposite sign (the calibrated catalogue's).
  add_test(NAME rocking_experiments_yaw
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/experiments_yaw.sh
                   $<TARGET_FILE:rocking_experiments> ${ROCKING_EXPERIMENTS_DIR}/granite_pbr
                   ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/granite_specimens_3d.yaml)
  set_tests_properties(rocking_experiments_yaw PROPERTIES TIMEOUT 120 SKIP_RETURN_CODE 77)
endif()
