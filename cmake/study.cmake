# rocking_study: the paper's study over every record (issue 5). Included by the top CMakeLists.
#
# The ROS-free study logic (include/rocking_monitor/core/study.hpp, src/core/study.cpp) is part of
# rocking_monitor_core (src/core/*.cpp is globbed); it runs its cases on std::thread workers, so the
# core links the platform thread library. The YAML body files and the JSON summary need yaml-cpp and
# nlohmann-json: they are in the small rocking_study_io library, linked by the tool and the tests.

find_package(Threads REQUIRED)
find_package(yaml-cpp REQUIRED)
target_link_libraries(rocking_monitor_core PUBLIC Threads::Threads)

add_library(rocking_study_io STATIC ${CMAKE_CURRENT_SOURCE_DIR}/src/study/study_io.cpp)
target_link_libraries(rocking_study_io PUBLIC rocking_monitor_core PRIVATE nlohmann_json::nlohmann_json)
# Debian's yaml-cpp 0.7 exports the plain target name `yaml-cpp` (later versions: yaml-cpp::yaml-cpp).
if(TARGET yaml-cpp::yaml-cpp)
  target_link_libraries(rocking_study_io PRIVATE yaml-cpp::yaml-cpp)
else()
  target_link_libraries(rocking_study_io PRIVATE yaml-cpp)
endif()
target_compile_options(rocking_study_io PRIVATE -Wall -Wextra -Wpedantic)
set_target_properties(rocking_study_io PROPERTIES POSITION_INDEPENDENT_CODE ON)

add_executable(rocking_study ${CMAKE_CURRENT_SOURCE_DIR}/src/tools/rocking_study.cpp)
target_link_libraries(rocking_study PRIVATE rocking_study_io rocking_monitor_core CLI11::CLI11)
target_compile_definitions(rocking_study PRIVATE ROCKING_RECORDS_DIR="${ROCKING_RECORDS_DIR}")
target_compile_options(rocking_study PRIVATE -Wall -Wextra -Wpedantic)
set_target_properties(rocking_study PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${ROCKING_TOOL_DIR})

if(BUILD_TESTING)
  # test/core/test_study.cpp is globbed into core_tests; it also exercises the YAML/JSON part.
  if(TARGET core_tests)
    target_link_libraries(core_tests PRIVATE rocking_study_io)
  endif()
  # The command-line tests need the rocking_study binary: a separate target with its path.
  find_package(GTest REQUIRED)
  include(GoogleTest)
  add_executable(study_cli_tests ${CMAKE_CURRENT_SOURCE_DIR}/test/study/test_study_cli.cpp)
  target_link_libraries(study_cli_tests PRIVATE rocking_monitor_core GTest::gtest_main
                        nlohmann_json::nlohmann_json)
  target_compile_definitions(study_cli_tests PRIVATE
    ROCKING_RECORDS_DIR="${ROCKING_RECORDS_DIR}"
    ROCKING_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}"
    ROCKING_STUDY_EXE="$<TARGET_FILE:rocking_study>"
    ROCKING_PYTHON="/usr/bin/python3")
  target_include_directories(study_cli_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/test/core)
  add_dependencies(study_cli_tests rocking_study)
  gtest_discover_tests(study_cli_tests DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 900)
endif()
