# Your own objects (issue 43): a scan or an inventory spreadsheet to a checked catalogue entry.
# catalogue_check loads a catalogue with the node's parser and prints its error or (--json) what the
# monitor derives per item and plane; scripts/rocking_catalogue (from-table, check) and
# scripts/rocking_geometry.py (meshes in PLY, STL, OBJ, OFF, glTF/GLB) call it.
add_executable(catalogue_check src/tools/catalogue_check.cpp)
target_link_libraries(catalogue_check PRIVATE rocking_monitor_core CLI11::CLI11 nlohmann_json::nlohmann_json)
target_compile_options(catalogue_check PRIVATE -Wall -Wextra -Wpedantic)
set_target_properties(catalogue_check PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${ROCKING_TOOL_DIR})

if(catkin_FOUND)
  install(TARGETS catalogue_check RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
  catkin_install_python(PROGRAMS scripts/rocking_catalogue scripts/rocking_geometry.py
                        DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
  # imported by the two above from beside them
  install(FILES scripts/rocking_geometry_solid.py scripts/mesh_input.py scripts/scan_entry.py scripts/scan_figure.py scripts/catalogue_table.py
                scripts/progress_bar.py DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
endif()

if(BUILD_TESTING)
  # Meshes made in the test with closed-form mass properties (box, cylinder, a turned and moved L) in
  # every format, mm and m, open and closed; each bad-mesh class's message; the granite specimens
  # through every format give today's entries (skipped with a notice without ../shared).
  add_test(NAME own_objects.scans_match_closed_forms
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/test_mesh_input.py
                   ${ROCKING_EXPERIMENTS_DIR}/granite_pbr)
  set_tests_properties(own_objects.scans_match_closed_forms PROPERTIES TIMEOUT 120 SKIP_RETURN_CODE 77)
  # A 100-row spreadsheet round-trips through the YAML; the node's parser accepts it and its errors
  # come back as row and column; check's numbers against closed forms; the floor plan.
  add_test(NAME own_objects.spreadsheet_round_trip
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/test_rocking_catalogue.py
                   $<TARGET_FILE:catalogue_check>)
  set_tests_properties(own_objects.spreadsheet_round_trip PROPERTIES TIMEOUT 120)
  add_test(NAME cli.catalogue_check.unknown_flag_is_one_error_line
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/unknown_flag.sh catalogue_check $<TARGET_FILE:catalogue_check>)
endif()

# The monitor node starts on a catalogue rocking_catalogue wrote (test/ros/own_objects.test).
if(catkin_FOUND AND CATKIN_ENABLE_TESTING AND TARGET monitor)
  find_package(rostest REQUIRED)
  add_rostest(test/ros/own_objects.test DEPENDENCIES monitor)
endif()
