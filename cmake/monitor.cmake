# The live monitor: library (RockingMonitor), node and nodelet shims, and its tests.
include_directories(${catkin_INCLUDE_DIRS})
add_library(rocking_monitor_ros
  src/ros/monitor.cpp src/ros/monitor_sample_path.cpp src/ros/monitor_publication.cpp
  src/ros/monitor_diagnostics.cpp src/ros/monitor_journal.cpp src/ros/monitor_snapshot.cpp src/ros/monitor_catch_up.cpp
  src/ros/catalogue.cpp)
target_include_directories(rocking_monitor_ros PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include ${catkin_INCLUDE_DIRS})
find_package(TBB REQUIRED)
target_link_libraries(rocking_monitor_ros PUBLIC rocking_monitor_core ${catkin_LIBRARIES} TBB::tbb)
add_dependencies(rocking_monitor_ros ${PROJECT_NAME}_generate_messages_cpp)

add_executable(monitor src/ros/monitor_node.cpp)
target_link_libraries(monitor PRIVATE rocking_monitor_ros)

add_library(rocking_monitor_nodelet src/ros/monitor_nodelet.cpp)
target_link_libraries(rocking_monitor_nodelet PRIVATE rocking_monitor_ros)

install(TARGETS monitor rocking_monitor_nodelet rocking_monitor_ros
        RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION}
        LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
        ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
install(FILES nodelet_plugins.xml DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
install(DIRECTORY launch config bags DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}
        PATTERN "historical" EXCLUDE)

# ---------------------------------------------------------------- tests
if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(catalogue_tests test/ros/test_catalogue.cpp)
  target_link_libraries(catalogue_tests rocking_monitor_ros)
  # The example catalogues are read as rosparam would (yaml-cpp into XmlRpc) and parsed.
  if(TARGET yaml-cpp::yaml-cpp)
    target_link_libraries(catalogue_tests yaml-cpp::yaml-cpp)
  else()
    target_link_libraries(catalogue_tests yaml-cpp)
  endif()
  target_compile_definitions(catalogue_tests PRIVATE ROCKING_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")

  find_package(rostest REQUIRED)
  add_rostest_gtest(test_monitor_replay test/ros/monitor_replay.test test/ros/test_monitor_replay.cpp
                  test/support/rostest_main.cpp)
  target_link_libraries(test_monitor_replay rocking_monitor_ros ${catkin_LIBRARIES})
  add_rostest(test/ros/monitor_states_rate.test DEPENDENCIES monitor)
  add_rostest(test/ros/monitor_nodelet.test DEPENDENCIES test_monitor_replay rocking_monitor_nodelet)
  add_rostest(test/ros/monitor_adaptive.test DEPENDENCIES test_monitor_replay rocking_monitor_nodelet)
  add_rostest(test/ros/monitor_ensemble.test DEPENDENCIES test_monitor_replay monitor)
  add_rostest(test/ros/monitor_ensemble_gain.test DEPENDENCIES test_monitor_replay monitor)
  add_rostest_gtest(test_monitor_sharded test/ros/monitor_sharded.test test/ros/test_monitor_sharded.cpp
                  test/support/rostest_main.cpp)
  target_link_libraries(test_monitor_sharded ${catkin_LIBRARIES})
  add_dependencies(test_monitor_sharded monitor)
  add_rostest_gtest(test_monitor_accel test/ros/monitor_accel.test test/ros/test_monitor_accel.cpp
                  test/support/rostest_main.cpp)
  target_link_libraries(test_monitor_accel rocking_monitor_ros ${catkin_LIBRARIES})
  add_rostest_gtest(test_monitor_bad_input test/ros/monitor_bad_input.test test/ros/test_monitor_bad_input.cpp
                  test/support/rostest_main.cpp)
  target_link_libraries(test_monitor_bad_input rocking_monitor_ros ${catkin_LIBRARIES})
endif()

if(CATKIN_ENABLE_TESTING)
  # Needs the records (skips with a notice without them) and the record_to_bag / rocking_sim tools.
  add_executable(test_monitor_historical EXCLUDE_FROM_ALL test/ros/test_monitor_historical.cpp test/support/rostest_main.cpp)
  target_link_libraries(test_monitor_historical rocking_monitor_ros ${catkin_LIBRARIES} GTest::gtest
                        nlohmann_json::nlohmann_json)
  target_include_directories(test_monitor_historical PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/test/support)
  add_dependencies(tests test_monitor_historical)
  if(TARGET record_to_bag)
    add_dependencies(test_monitor_historical record_to_bag rocking_sim)
  endif()
  add_rostest(test/ros/monitor_historical.test DEPENDENCIES test_monitor_historical)
  # Issue 19: kill -9 after an OVERTURNED alarm, a cut journal line, restart: alarms once (Python).
  add_rostest(test/ros/monitor_journal.test DEPENDENCIES monitor)
  # Issue 29: kill -9 during the strong motion, restart: the items continue from the state snapshot;
  # damaged, foreign and stale snapshots refused (Python; uses monitor_journal.py's helpers).
  add_rostest(test/ros/monitor_restart.test DEPENDENCIES monitor)
  add_rostest(test/ros/monitor_restart.test ARGS kill_after:=1.0 DEPENDENCIES monitor)
  add_rostest(test/ros/monitor_restart.test ARGS catch_up:=false catch_up_service:=/no_bridge/history DEPENDENCIES monitor)
  # Issue 29 part 2: killed twice mid strong motion, caught up from ground_motion_player's ~history:
  # the unbroken control's alarms exactly.
  add_rostest(test/ros/monitor_catch_up.test DEPENDENCIES monitor ground_motion_player)
  # ... killed just before alarms (the shelving unit's COMMITTED at 0.95 s, the rack's OVERTURNED at 2.56 s):
  # raised while catching up.
  add_rostest(test/ros/monitor_catch_up.test ARGS kill_after:=0.93_2.5 DEPENDENCIES monitor ground_motion_player)
  # ... also when restarted 3 s later (beyond ~max_bridge: without the history the snapshot is stale).
  # (catkin names the result file from the arguments up to the first '.': restart_delay first keeps it
  # apart from kill_after:=0.93_2.5's, which ctest -j would otherwise overwrite.)
  add_rostest(test/ros/monitor_catch_up.test ARGS restart_delay:=3.0 kill_after:=0.3 DEPENDENCIES monitor ground_motion_player)
  # ... and a history shorter than the restart: the frozen gap, said in the log and /diagnostics.
  add_rostest(test/ros/monitor_catch_up.test ARGS history_length:=0.1 expect_catch_up:=false kill_after:=0.3
              DEPENDENCIES monitor ground_motion_player)
  # ... and a history service that does not answer: given up after ~catch_up_timeout, the frozen gap.
  add_rostest(test/ros/monitor_catch_up.test ARGS catch_up_service:=/slow_bridge/history catch_up_timeout:=1.0
              expect_catch_up:=false kill_after:=0.3 DEPENDENCIES monitor ground_motion_player)
  # Issue 29 part 4: the same record twice, 60 s of quiet apart: two events, every level alarmed in both.
  add_rostest(test/ros/monitor_aftershock.test DEPENDENCIES monitor)
  # Issue 29 part 3: launch/monitor_pair.launch, one of the pair killed with SIGKILL during the strong
  # motion and respawned (a 0.3 s in, b 1.0 s in, a 2.0 s in: between the alarms): the deduplicated
  # alarms (scripts/alarm_dedup.py, the dashboard) are the unbroken control's.
  add_rostest(test/ros/monitor_pair.test DEPENDENCIES monitor)
  add_rostest(test/ros/monitor_pair.test ARGS kill:=b kill_after:=1.0 DEPENDENCIES monitor)
  add_rostest(test/ros/monitor_pair.test ARGS kill:=a kill_after:=2.0 DEPENDENCIES monitor)
  # The pair's rule for "the same alarm" (consumers show each once), on plain objects: no ROS needed.
  add_test(NAME alarm_dedup.same_alarm_from_either_monitor_shown_once
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/test_alarm_dedup.py
                   ${CMAKE_CURRENT_SOURCE_DIR}/scripts)
  # Issue 28: ~state_changes applied to one ~states give the last ~states (Python).
  add_rostest(test/ros/monitor_state_changes.test DEPENDENCIES monitor)
endif()

# ---------------------------------------------------------------- the live dashboard (issue 14)
# cpp-httplib as Debian builds it (a shared library; its pkg-config flags carry the TLS/zlib defines
# that fix its class layout, so they must be used as given).
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(CPP_HTTPLIB QUIET IMPORTED_TARGET cpp-httplib)
endif()
if(CPP_HTTPLIB_FOUND)
  # The page's files (src/ros/dashboard_web/) become raw string literals included by dashboard_assets.cpp.
  set(dashboard_web_inc)
  foreach(asset index.html style.css app.js state.js plan.js item_view.js alarms.js health.js)
    set(out ${CMAKE_CURRENT_BINARY_DIR}/dashboard_web/${asset}.inc)
    add_custom_command(OUTPUT ${out}
      COMMAND ${CMAKE_COMMAND} -DIN=${CMAKE_CURRENT_SOURCE_DIR}/src/ros/dashboard_web/${asset} -DOUT=${out}
              -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/embed_asset.cmake
      DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/ros/dashboard_web/${asset} ${CMAKE_CURRENT_SOURCE_DIR}/cmake/embed_asset.cmake
      COMMENT "embedding dashboard asset ${asset}")
    list(APPEND dashboard_web_inc ${out})
  endforeach()
  add_library(rocking_dashboard
    src/ros/dashboard.cpp src/ros/dashboard_state.cpp src/ros/dashboard_http.cpp
    src/ros/dashboard_events.cpp src/ros/dashboard_assets.cpp src/ros/dashboard_input.cpp
    src/ros/dashboard_journal.cpp ${dashboard_web_inc})
  target_include_directories(rocking_dashboard PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include ${catkin_INCLUDE_DIRS})
  target_include_directories(rocking_dashboard PRIVATE ${CMAKE_CURRENT_BINARY_DIR})
  target_link_libraries(rocking_dashboard PUBLIC rocking_monitor_ros PkgConfig::CPP_HTTPLIB
                        nlohmann_json::nlohmann_json Threads::Threads)
  add_executable(dashboard src/ros/dashboard_node.cpp)
  target_link_libraries(dashboard PRIVATE rocking_dashboard)
  install(TARGETS dashboard rocking_dashboard
          RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION}
          LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
          ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
  if(CATKIN_ENABLE_TESTING)
    add_rostest_gtest(test_dashboard test/ros/dashboard.test test/ros/test_dashboard.cpp
                  test/support/rostest_main.cpp)
    target_link_libraries(test_dashboard rocking_dashboard ${catkin_LIBRARIES})
    add_dependencies(test_dashboard dashboard monitor)
    add_rostest(test/ros/dashboard_restart.test DEPENDENCIES dashboard monitor)
    add_rostest(test/ros/dashboard_ensemble.test DEPENDENCIES test_dashboard)
    # Issue 54: idle connections and oversize or unsized bodies do not starve the page (Python, raw sockets).
    add_rostest(test/ros/dashboard_limits.test DEPENDENCIES dashboard)
    # The page in a real browser (Debian chromium, scripts/install_deps.sh); skipped with a notice without it.
    find_program(CHROMIUM_EXECUTABLE chromium)
    if(CHROMIUM_EXECUTABLE)
      # The test is Python: ctest does not source devel/setup.bash, so it is told where the generated
      # message modules are.
      add_rostest(test/ros/dashboard_browser.test DEPENDENCIES dashboard monitor)
      # the same page with an item the 3-D model decides (its detail, tilt and "3d" alarms)
      add_rostest(test/ros/dashboard_browser_3d.test DEPENDENCIES dashboard monitor)
      # hostile text (<script>, <img onerror>) from the catalogue and the topics shown as text, never run
      add_rostest(test/ros/dashboard_escaping.test DEPENDENCIES dashboard)
    else()
      message(STATUS "chromium not found: the dashboard's browser test (test/ros/dashboard_browser.test) is not run")
    endif()
  endif()
else()
  message(WARNING "cpp-httplib not found (Debian: libcpp-httplib-dev; scripts/install_deps.sh): "
                  "the dashboard node is not built")
endif()

if(CATKIN_ENABLE_TESTING)
  # Issue 19: the fault table (bad stamps, clock step, transport loss) on the Rinaldi record.
  add_executable(test_monitor_faults EXCLUDE_FROM_ALL test/ros/test_monitor_faults.cpp test/support/rostest_main.cpp)
  target_link_libraries(test_monitor_faults rocking_monitor_ros ${catkin_LIBRARIES} GTest::gtest)
  target_include_directories(test_monitor_faults PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/test/support)
  add_dependencies(tests test_monitor_faults)
  if(TARGET record_to_bag)
    add_dependencies(test_monitor_faults record_to_bag monitor)
  endif()
  add_rostest(test/ros/monitor_faults.test DEPENDENCIES test_monitor_faults)
  # The same faults with ~restamp_in_sequence false: the bad-stamped samples are dropped.
  add_rostest(test/ros/monitor_faults.test ARGS restamp:=false DEPENDENCIES test_monitor_faults)
endif()
if(CATKIN_ENABLE_TESTING)
  # Issue 19 part 3: overload visible, load shed, every sample stepped or counted.
  add_rostest_gtest(test_monitor_overload test/ros/monitor_overload.test test/ros/test_monitor_overload.cpp
                  test/support/rostest_main.cpp)
  target_link_libraries(test_monitor_overload ${catkin_LIBRARIES})
  add_dependencies(test_monitor_overload monitor)
endif()
