# The install space beyond what each part installs itself (issue 30 part 2, checked by
# test/tools/install_space.sh): the command-line tools, the live table demo.launch starts, and the
# ROS-free core for downstream packages (its static libraries and headers; what they link is found by
# cmake/rocking_monitor-extras.cmake).
if(NOT catkin_FOUND)
  return()
endif()
install(TARGETS rocking_sim rocking_study rocking_experiments RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
catkin_install_python(PROGRAMS scripts/monitor_table.py DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(TARGETS ${ROCKING_CORE_LAYERS} ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
install(DIRECTORY include/rocking_monitor/ DESTINATION ${CATKIN_PACKAGE_INCLUDE_DESTINATION})
