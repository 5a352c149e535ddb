# Tests of the package as a whole: the core's layering and the scripts' imports, package.xml's
# dependencies, the documentation's links and every executable's voice on a bad flag.
if(NOT BUILD_TESTING)
  return()
endif()

add_test(NAME layers.core_keeps_its_layering
         COMMAND ${CMAKE_COMMAND} -DROOT=${CMAKE_CURRENT_SOURCE_DIR} -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/check_layers.cmake)
add_test(NAME layers.check_names_wrong_way_includes
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/check_layers_detects.sh ${CMAKE_CURRENT_SOURCE_DIR})
# The same for scripts/ (issue 53): no Python script imports one that imports it back.
add_test(NAME layers.scripts_have_no_import_circle
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/check_script_imports.py ${CMAKE_CURRENT_SOURCE_DIR}/scripts)
add_test(NAME layers.import_check_names_a_circle
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/check_script_imports_detects.sh ${CMAKE_CURRENT_SOURCE_DIR})
set_tests_properties(layers.scripts_have_no_import_circle layers.import_check_names_a_circle PROPERTIES TIMEOUT 60)

# package.xml declares what scripts/install_deps.sh installs, and no more (rosdep users get the same).
add_test(NAME package.deps_match_install_deps
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/check_package_deps.py ${CMAKE_CURRENT_SOURCE_DIR})
add_test(NAME package.deps_check_names_mismatches
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/check_package_deps_detects.sh ${CMAKE_CURRENT_SOURCE_DIR})
set_tests_properties(package.deps_match_install_deps package.deps_check_names_mismatches PROPERTIES TIMEOUT 60)

# README.md is the front door into docs/ (issue 30): every relative link and #anchor there leads somewhere.
add_test(NAME docs.links_resolve
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/check_doc_links.py ${CMAKE_CURRENT_SOURCE_DIR})
add_test(NAME docs.link_check_names_dead_links
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/check_doc_links_detects.sh ${CMAKE_CURRENT_SOURCE_DIR})
set_tests_properties(docs.links_resolve docs.link_check_names_dead_links PROPERTIES TIMEOUT 60)

# A ROS user's install space: every launched node, the tools, launch files resolved there, and a
# downstream package built against the installed core (test/tools/install_space.sh).
if(catkin_FOUND)
  add_test(NAME install.space_serves_a_ros_user
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/install_space.sh ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_BINARY_DIR})
  set_tests_properties(install.space_serves_a_ros_user PROPERTIES TIMEOUT 600)
endif()

foreach(tool rocking_sim rocking_study record_to_bag rocking_accuracy rocking_benchmarks)
  if(TARGET ${tool})
    add_test(NAME cli.${tool}.unknown_flag_is_one_error_line
             COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/unknown_flag.sh ${tool} $<TARGET_FILE:${tool}>)
  endif()
endforeach()

# --help byte for byte as test/tools/expected/<tool>.help (issue 53: the mains are parse + run).
foreach(tool rocking_sim rocking_study rocking_experiments rocking_accuracy record_to_mseed record_to_bag)
  if(TARGET ${tool})
    add_test(NAME cli.${tool}.help_unchanged
             COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/help_unchanged.sh $<TARGET_FILE:${tool}>
                     ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/expected/${tool}.help ${ROCKING_RECORDS_DIR})
    set_tests_properties(cli.${tool}.help_unchanged PROPERTIES TIMEOUT 60)
  endif()
endforeach()

# The long tools' progress: only on a terminal (a pseudo-terminal from script(1)), never with --quiet,
# never off a terminal (issue 53; src/tools/progress_meter.*).
if(TARGET rocking_study AND TARGET rocking_experiments AND TARGET rocking_accuracy)
  add_test(NAME tools.progress_only_on_a_terminal
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/progress_only_on_a_terminal.sh ${ROCKING_TOOL_DIR}
                   ${ROCKING_EXPERIMENTS_DIR}/granite_pbr ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/granite_specimens.yaml
                   ${ROCKING_RECORDS_DIR})
  set_tests_properties(tools.progress_only_on_a_terminal PROPERTIES TIMEOUT 120 SKIP_RETURN_CODE 77)
endif()

# The study writes the same bytes as before the layout change (needs the shared records).
if(TARGET rocking_study)
  add_test(NAME study.small_grid_byte_identical
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/study_byte_identical.sh $<TARGET_FILE:rocking_study>
                   ${ROCKING_RECORDS_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/expected/study_small_grid.sha256)
  # ... and so does it in shards, under GNU parallel and as a Slurm array job, merged.
  add_test(NAME study.sharded_byte_identical
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/study_sharded_byte_identical.sh $<TARGET_FILE:rocking_study>
                   ${ROCKING_RECORDS_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/test/tools/expected/study_small_grid.sha256
                   ${CMAKE_CURRENT_SOURCE_DIR}/scripts)
endif()
