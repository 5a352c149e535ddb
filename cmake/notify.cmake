# The notify layer (issue 44, docs/notify.md): the alarm notifier's ROS-free core and its channels.
# libcurl (Debian libcurl4-openssl-dev) speaks SMTP and HTTP, libmosquitto (libmosquitto-dev) MQTT,
# yaml-cpp reads the routing, nlohmann-json writes the outbox and the webhook bodies.
find_package(PkgConfig REQUIRED)
pkg_check_modules(ROCKING_CURL REQUIRED IMPORTED_TARGET libcurl)
pkg_check_modules(ROCKING_MOSQUITTO REQUIRED IMPORTED_TARGET libmosquitto)
target_link_libraries(rocking_monitor_notify PUBLIC Threads::Threads
  PRIVATE PkgConfig::ROCKING_CURL PkgConfig::ROCKING_MOSQUITTO nlohmann_json::nlohmann_json)
if(TARGET yaml-cpp::yaml-cpp)
  target_link_libraries(rocking_monitor_notify PRIVATE yaml-cpp::yaml-cpp)
else()
  target_link_libraries(rocking_monitor_notify PRIVATE yaml-cpp)
endif()

# notify_tests: the core's gtests; test/notify/notify_servers_test.cpp drives the core against real
# servers it starts on loopback (python3-aiosmtpd, mosquitto, python3's http.server: test/notify/servers.py).
if(BUILD_TESTING)
  find_package(GTest REQUIRED)
  include(GoogleTest)
  file(GLOB ROCKING_NOTIFY_TESTS CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/test/notify/*.cpp)
  add_executable(notify_tests ${ROCKING_NOTIFY_TESTS})
  target_link_libraries(notify_tests PRIVATE rocking_monitor_notify GTest::gtest_main nlohmann_json::nlohmann_json
                        PkgConfig::ROCKING_MOSQUITTO)
  target_compile_definitions(notify_tests PRIVATE
    ROCKING_NOTIFY_SERVERS="${CMAKE_CURRENT_SOURCE_DIR}/test/notify/servers.py"
    ROCKING_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  gtest_discover_tests(notify_tests DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 120)
endif()

# alarm_notifier: the ROS node around the core (src/ros/alarm_notifier*.cpp) and its rostest.
if(catkin_FOUND)
  add_executable(alarm_notifier src/ros/alarm_notifier.cpp src/ros/alarm_notifier_node.cpp)
  target_include_directories(alarm_notifier PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/include ${catkin_INCLUDE_DIRS})
  target_link_libraries(alarm_notifier PRIVATE rocking_monitor_notify ${catkin_LIBRARIES})
  target_compile_options(alarm_notifier PRIVATE -Wall -Wextra)
  add_dependencies(alarm_notifier ${PROJECT_NAME}_generate_messages_cpp)
  install(TARGETS alarm_notifier RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
endif()
if(catkin_FOUND AND CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  # The demo's pulse through the monitor and the node to real servers; the node killed and restarted; a pair.
  add_rostest(test/ros/alarm_notifier.test DEPENDENCIES alarm_notifier monitor)
endif()
