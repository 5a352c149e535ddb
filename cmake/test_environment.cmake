# The environment of every test. Included last, so that it sees every test.
#  - A ROS_HOME of its own under build/test_ros_home/, emptied before the tests run: the monitor's
#    alarm journal (default $ROS_HOME/rocking_monitor/journal.jsonl, docs/journal.md) must not carry
#    one test's (or one run's, or another checkout's) alarms into another.
#  - Where the records, the tools, the generated Python messages and test outputs are: the rostests
#    read them with $(env ...) rather than as rostest ARGS, which catkin puts into the test's target
#    and file names (beyond 255 characters in a deep checkout). ctest does not source setup.bash.
#  - One lock per rostest file: rostest writes the test node's results to TEST-<test-name>.xml,
#    the same file for every registration of one .test file with other ARGS, and deletes it when a
#    run starts; two such runs at once under ctest -j delete each other's results ("did not generate
#    test results", seen in CI on monitor_catch_up).
#  - A base for the UDP/TCP ports the rostests bind (bridges, the SeedLink test server), from the
#    build directory's path: two checkouts testing on one machine at once must not share a port.
#    20000-31990, below Linux's ephemeral ports (32768-60999); the tests use base + 1 .. base + 9.
if(CATKIN_ENABLE_TESTING OR BUILD_TESTING)
  string(MD5 _dir_hash "${CMAKE_BINARY_DIR}")
  string(SUBSTRING "${_dir_hash}" 0 4 _dir_hash)
  math(EXPR ROCKING_TEST_PORT_BASE "20000 + (0x${_dir_hash} % 1200) * 10")
  add_test(NAME test_ros_home.clean COMMAND ${CMAKE_COMMAND} -E rm -rf ${CMAKE_BINARY_DIR}/test_ros_home)
  set_tests_properties(test_ros_home.clean PROPERTIES FIXTURES_SETUP test_ros_home)
  get_property(_all_tests DIRECTORY PROPERTY TESTS)
  foreach(_test IN LISTS _all_tests)
    if(_test STREQUAL "test_ros_home.clean")
      continue()
    endif()
    string(MAKE_C_IDENTIFIER "${_test}" _id)
    string(SUBSTRING "${_id}" 0 80 _id)
    string(MD5 _hash "${_test}")
    string(SUBSTRING "${_hash}" 0 8 _hash)
    set_property(TEST ${_test} APPEND PROPERTY ENVIRONMENT "ROS_HOME=${CMAKE_BINARY_DIR}/test_ros_home/${_id}_${_hash}")
    set_property(TEST ${_test} APPEND PROPERTY FIXTURES_REQUIRED test_ros_home)
    set_property(TEST ${_test} APPEND PROPERTY ENVIRONMENT
                 "ROCKING_RECORDS_DIR=${ROCKING_RECORDS_DIR}" "ROCKING_TOOL_DIR=${ROCKING_TOOL_DIR}"
                 "ROCKING_PYTHON_PATH=${CATKIN_DEVEL_PREFIX}/${PYTHON_INSTALL_DIR}"
                 "ROCKING_TEST_OUTPUT_DIR=${CMAKE_BINARY_DIR}/test_results"
                 "ROCKING_TEST_PORT_BASE=${ROCKING_TEST_PORT_BASE}")
    # catkin names a rostest _ctest_<pkg>_rostest_test_ros_<file>.test, or with ARGS <file>__<args>
    if(_test MATCHES "^_ctest_${PROJECT_NAME}_rostest_(test_ros_)?([A-Za-z0-9]+(_[A-Za-z0-9]+)*)(\\.test|__)")
      set_property(TEST ${_test} PROPERTY RESOURCE_LOCK "rostest_${CMAKE_MATCH_2}")
    endif()
  endforeach()
endif()

# catkin builds its test executables (catkin_add_gtest, add_rostest_gtest) only with the `tests`
# target, after `all`: two builds one after the other, each with its serial tail, and a plain
# `cmake --build` that leaves the rostests' nodes missing. In `all` they build beside the rest
# (issue 42 part 4); `tests` then has nothing left to do.
if(TARGET tests)
  get_property(_test_targets TARGET tests PROPERTY MANUALLY_ADDED_DEPENDENCIES)
  foreach(_target IN LISTS _test_targets)
    if(TARGET ${_target})
      get_target_property(_type ${_target} TYPE)
      if(_type STREQUAL "EXECUTABLE")
        set_target_properties(${_target} PROPERTIES EXCLUDE_FROM_ALL FALSE)
      endif()
    endif()
  endforeach()
endif()
