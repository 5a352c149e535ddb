# The post-event report (issue 14, part 2): scripts/rocking_report (Python: rosbag, numpy, matplotlib)
# and its tests. The monitor's launch files start it as a node with report_dir:=DIR.
catkin_install_python(PROGRAMS scripts/rocking_report DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
# The redundant pair's "one alarm" rule, imported by rocking_report and monitor_table.py from beside them.
install(FILES scripts/alarm_dedup.py DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
# rocking_report's parts (issue 53), imported from beside it as alarm_dedup.py is.
install(DIRECTORY scripts/event_report DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION} FILES_MATCHING PATTERN "*.py")
if(CATKIN_ENABLE_TESTING)
  # No ROS master: bad input is one error line; the spectrum and the Housner periods from independent sources.
  add_test(NAME report.bad_input_is_one_error_line
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/report_bad_input.sh
                   ${CMAKE_CURRENT_SOURCE_DIR}/scripts/rocking_report ${CMAKE_CURRENT_SOURCE_DIR})
  if(TARGET rocking_sim)
    add_test(NAME report.spectrum_and_periods_match_closed_forms_and_core
             COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/test_report_method.py
                     ${CMAKE_CURRENT_SOURCE_DIR}/scripts/rocking_report $<TARGET_FILE:rocking_sim>
                     ${CMAKE_CURRENT_SOURCE_DIR}/config/catalogue_example.yaml
                     ${CMAKE_CURRENT_SOURCE_DIR}/bags/one_sine_pulse.csv)
  endif()
  # --pair (a redundant pair): both monitors' alarms from a bag, each once (needs the generated messages).
  add_test(NAME report.pair_alarms_each_once
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/test_report_pair.py
                   ${CMAKE_CURRENT_SOURCE_DIR}/scripts/rocking_report)
  # An item on a support (issue 51): "fell off its support" and the support margin (needs the generated messages).
  add_test(NAME report.fell_off_support_and_support_margin
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/test_report_support.py
                   ${CMAKE_CURRENT_SOURCE_DIR}/scripts/rocking_report)
  # The report written by the node after the pulse replay equals the monitor's alarms and states.
  if(TARGET monitor)
    # From record files and a catalogue (no bag): record_to_bag, replay, the node's report.
    add_test(NAME report.from_record_files
             COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/report_from_record.sh ${CMAKE_CURRENT_SOURCE_DIR})
    set_tests_properties(report.from_record_files PROPERTIES TIMEOUT 180)
    add_rostest(test/ros/report.test DEPENDENCIES monitor)
  endif()
endif()
