# Ground-motion records on ROS (issue 3): record_to_bag, ground_motion_player, the committed synthetic
# bags and the historical-earthquake bags, and their tests. Included by CMakeLists.txt when catkin is
# found. See bags/README.md and docs/records.md.
find_package(yaml-cpp REQUIRED)

# Sources of ground motion + message filling, shared by the tool and the node.
# A bridge's recent samples served as ~history (issue 29 part 2): the player and both bridges.
add_library(rocking_history_ros STATIC src/ros/sample_history_server.cpp)
target_include_directories(rocking_history_ros PUBLIC
  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> ${catkin_INCLUDE_DIRS})
target_link_libraries(rocking_history_ros PUBLIC rocking_monitor_feeds ${catkin_LIBRARIES})
target_compile_options(rocking_history_ros PRIVATE -Wall -Wextra)
set_target_properties(rocking_history_ros PROPERTIES POSITION_INDEPENDENT_CODE ON)
add_dependencies(rocking_history_ros ${PROJECT_NAME}_generate_messages_cpp)  # SampleHistory.srv

add_library(rocking_records_ros STATIC src/ros/ground_motion_source.cpp src/ros/ground_motion_player.cpp)
target_include_directories(rocking_records_ros PUBLIC
  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> ${catkin_INCLUDE_DIRS})
target_link_libraries(rocking_records_ros PUBLIC rocking_history_ros rocking_monitor_core ${catkin_LIBRARIES} yaml-cpp)
target_compile_options(rocking_records_ros PRIVATE -Wall -Wextra)
set_target_properties(rocking_records_ros PROPERTIES POSITION_INDEPENDENT_CODE ON)
# default of record_to_bag --records-dir and the player's ~records_dir
target_compile_definitions(rocking_records_ros PRIVATE ROCKING_DEFAULT_RECORDS_DIR="${ROCKING_RECORDS_DIR}")

# record_to_bag.cpp parses the flags (record_to_bag_options.*) and runs one job; --list and --all in
# record_to_bag_directory.cpp, the bag and CSV in record_to_bag_writing.*.
add_executable(record_to_bag src/tools/record_to_bag.cpp src/tools/record_to_bag_options.cpp
                             src/tools/record_to_bag_directory.cpp src/tools/record_to_bag_writing.cpp)
target_link_libraries(record_to_bag PRIVATE rocking_records_ros CLI11::CLI11)
target_compile_options(record_to_bag PRIVATE -Wall -Wextra)
# one unity source: CLI11 and the ROS headers compiled once
set_target_properties(record_to_bag PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${ROCKING_TOOL_DIR} UNITY_BUILD ON)

add_executable(ground_motion_player src/ros/ground_motion_player_node.cpp)
target_link_libraries(ground_motion_player PRIVATE rocking_records_ros)
target_compile_options(ground_motion_player PRIVATE -Wall -Wextra)
set_target_properties(ground_motion_player PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${ROCKING_TOOL_DIR})

install(TARGETS record_to_bag ground_motion_player RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

# ---------------------------------------------------------------- bags
# Historical earthquakes: one bag per station with 2+ components (105 of the 158 stations in
# ../shared/records), plus bags/historical/index.csv. Third-party data: git-ignored, never committed.
#   cmake --build build --target historical_bags
set(ROCKING_HISTORICAL_BAG_DIR ${CMAKE_CURRENT_SOURCE_DIR}/bags/historical)
add_custom_target(historical_bags
  COMMAND $<TARGET_FILE:record_to_bag> --all --records-dir ${ROCKING_RECORDS_DIR}
          --out-dir ${ROCKING_HISTORICAL_BAG_DIR} --min-components 2 --quiet
  DEPENDS record_to_bag
  COMMENT "Historical-earthquake bags from ${ROCKING_RECORDS_DIR} into bags/historical/"
  VERBATIM)

# The committed synthetic bags (bags/README.md), regenerated in the source tree:
#   cmake --build build --target synthetic_bags
set(ROCKING_BAGS ${CMAKE_CURRENT_SOURCE_DIR}/bags)
add_custom_target(synthetic_bags
  COMMAND $<TARGET_FILE:record_to_bag> --file ${ROCKING_BAGS}/one_sine_pulse.csv
          --out ${ROCKING_BAGS}/synthetic_one_sine_pulse.bag --compression bz2
  COMMAND $<TARGET_FILE:record_to_bag> --synthetic ${ROCKING_BAGS}/synthetic_ricker.yaml
          --out ${ROCKING_BAGS}/synthetic_ricker.bag --compression bz2
  COMMAND $<TARGET_FILE:record_to_bag> --synthetic ${ROCKING_BAGS}/synthetic_quiet_noise.yaml
          --out ${ROCKING_BAGS}/synthetic_quiet_noise.bag --compression bz2
  DEPENDS record_to_bag
  COMMENT "Synthetic bags in bags/"
  VERBATIM)

# ---------------------------------------------------------------- tests
if(CATKIN_ENABLE_TESTING AND BUILD_TESTING)
  find_package(GTest REQUIRED)
  include(GoogleTest)
  find_package(rostest REQUIRED)

  # record_to_bag end to end, read back with rosbag::View (no ROS master needed): RecordToBag.*
  add_executable(records_ros_tests EXCLUDE_FROM_ALL test/tools/test_record_to_bag.cpp)
  target_link_libraries(records_ros_tests PRIVATE rocking_records_ros GTest::gtest_main)
  target_compile_definitions(records_ros_tests PRIVATE
    ROCKING_RECORDS_DIR="${ROCKING_RECORDS_DIR}"
    RECORD_TO_BAG_EXE="$<TARGET_FILE:record_to_bag>"
    ROCKING_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  target_include_directories(records_ros_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/test/support)
  add_dependencies(records_ros_tests record_to_bag)
  if(TARGET tests)
    add_dependencies(tests records_ros_tests)
  endif()
  gtest_discover_tests(records_ros_tests DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

  # The live player under rostest: rate, content, end signal (wall time and sim time), and hztest.
  add_rostest_gtest(test_ground_motion_player test/ros/player.test test/ros/test_ground_motion_player.cpp)
  if(TARGET test_ground_motion_player)
    target_link_libraries(test_ground_motion_player rocking_records_ros ${catkin_LIBRARIES})
    target_compile_definitions(test_ground_motion_player PRIVATE ROCKING_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
    add_dependencies(test_ground_motion_player ground_motion_player)
    add_rostest(test/ros/player_sim_time.test DEPENDENCIES test_ground_motion_player ground_motion_player)
    add_rostest(test/ros/player_bad_param.test DEPENDENCIES test_ground_motion_player ground_motion_player)
  endif()
  add_rostest(test/ros/player_hztest.test DEPENDENCIES ground_motion_player)
endif()
