# The shaking-table bridge (ROS side of the feeds layer: datagrams, reorder window).
# udp_accel_bridge: a shaking-table controller's UDP stream -> sensor_msgs/Imu (README "Connect a shaking table")
add_executable(udp_accel_bridge src/ros/udp_accel_bridge.cpp src/ros/udp_accel_bridge_node.cpp)
target_include_directories(udp_accel_bridge PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/include ${catkin_INCLUDE_DIRS})
target_link_libraries(udp_accel_bridge PRIVATE rocking_history_ros rocking_monitor_feeds rocking_monitor_constants ${catkin_LIBRARIES} Threads::Threads)
target_compile_options(udp_accel_bridge PRIVATE -Wall -Wextra)
install(TARGETS udp_accel_bridge RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  # A real record sent as datagrams with seeded drops and reordering, text and binary.
  add_rostest(test/ros/udp_accel_bridge.test DEPENDENCIES udp_accel_bridge)
  # Issue 52: ~allowed_senders; intruders from another port and from 127.0.0.2 dropped and counted.
  add_rostest(test/ros/udp_allowed_senders.test DEPENDENCIES udp_accel_bridge)
  # Issue 52 item 2: ~key_file; no tag, a wrong key, a flipped bit and replays: 0 published, counted.
  add_rostest(test/ros/udp_authenticated.test DEPENDENCIES udp_accel_bridge)
  # Issue 52 item 3: a conflict keeps the first sample, is ERROR, and marks a held sample (variance inf).
  add_rostest(test/ros/udp_conflicts.test DEPENDENCIES udp_accel_bridge monitor)
  # Live == offline: the record through bridge and monitor equals rocking_sim on the files.
  add_rostest(test/ros/shaking_table_live_offline.test DEPENDENCIES udp_accel_bridge monitor rocking_sim)
endif()

