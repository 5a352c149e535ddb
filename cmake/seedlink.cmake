# Issue 18, SeedLink half: record_to_mseed (tool), seedlink_bridge (node) and their rostests.
# record_to_mseed.cpp parses the flags (record_to_mseed_options.*) and runs the one job (record_to_mseed_run.cpp).
add_executable(record_to_mseed src/tools/record_to_mseed.cpp src/tools/record_to_mseed_options.cpp
                               src/tools/record_to_mseed_run.cpp)
target_link_libraries(record_to_mseed PRIVATE rocking_monitor_core CLI11::CLI11)
target_compile_options(record_to_mseed PRIVATE -Wall -Wextra)
# one unity source: CLI11 (header only) compiled once
set_target_properties(record_to_mseed PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${ROCKING_TOOL_DIR} UNITY_BUILD ON)
if(BUILD_TESTING)
  add_test(NAME cli.record_to_mseed.unknown_flag_is_one_error_line
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/unknown_flag.sh record_to_mseed $<TARGET_FILE:record_to_mseed>)
  add_executable(record_to_mseed_tests test/tools/test_record_to_mseed.cpp)
  target_link_libraries(record_to_mseed_tests PRIVATE rocking_monitor_core GTest::gtest_main)
  target_include_directories(record_to_mseed_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/test/support)
  target_compile_definitions(record_to_mseed_tests PRIVATE ROCKING_RECORDS_DIR="${ROCKING_RECORDS_DIR}"
                             RECORD_TO_MSEED_EXE="$<TARGET_FILE:record_to_mseed>")
  add_dependencies(record_to_mseed_tests record_to_mseed)
  gtest_discover_tests(record_to_mseed_tests DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 120)
endif()

if(catkin_FOUND)
  add_executable(seedlink_bridge src/ros/seedlink_bridge_node.cpp src/ros/seedlink_bridge.cpp)
  target_include_directories(seedlink_bridge PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/include ${catkin_INCLUDE_DIRS})
  target_link_libraries(seedlink_bridge PRIVATE rocking_history_ros rocking_monitor_core ${catkin_LIBRARIES} Threads::Threads)
  install(TARGETS seedlink_bridge record_to_mseed RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
endif()

if(catkin_FOUND AND CATKIN_ENABLE_TESTING)
  # A real record over SeedLink into the monitor, with a server restart (needs the records; skips
  # with a notice without them).
  add_executable(test_seedlink_monitor EXCLUDE_FROM_ALL test/ros/test_seedlink_monitor.cpp test/support/rostest_main.cpp)
  target_link_libraries(test_seedlink_monitor rocking_monitor_ros ${catkin_LIBRARIES} GTest::gtest nlohmann_json::nlohmann_json)
  target_include_directories(test_seedlink_monitor PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/test/support)
  add_dependencies(tests test_seedlink_monitor)
  add_dependencies(test_seedlink_monitor seedlink_bridge record_to_mseed rocking_sim monitor)
  add_rostest(test/ros/seedlink_monitor.test DEPENDENCIES test_seedlink_monitor)
endif()

if(catkin_FOUND AND CATKIN_ENABLE_TESTING)
  add_rostest(test/ros/seedlink_bridge_bad_params.test DEPENDENCIES seedlink_bridge)
  # Issue 52 item 3: an overlapping record with other samples through the test server (the bundled pulse).
  add_rostest(test/ros/seedlink_conflict.test DEPENDENCIES seedlink_bridge record_to_mseed)
endif()
