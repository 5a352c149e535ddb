# reference_friction_tests: the frictional impact law (physics/frictional_impact.hpp) against Siconos
# numerics' fc3d solver (Debian's libsiconos-numerics-dev). Debian 12's Siconos CMake package
# imports targets of parts it does not ship (kernel, mechanics): the library is found directly.
if(BUILD_TESTING)
  find_path(ROCKING_SICONOS_INCLUDE siconos/numerics/FrictionContactProblem.h)
  find_library(ROCKING_SICONOS_NUMERICS siconos_numerics)
  if(ROCKING_SICONOS_INCLUDE AND ROCKING_SICONOS_NUMERICS)
    find_package(GTest REQUIRED)
    include(GoogleTest)
    # The frictional impact law against fc3d, and the 3-D model's friction over whole motions against a
    # Moreau-Jean time-stepping reference built on fc3d (test/reference/moreau_jean_body.*).
    add_executable(reference_friction_tests test/reference/test_siconos_friction.cpp
                   test/reference/test_moreau_jean_friction.cpp test/reference/moreau_jean_body.cpp)
    target_include_directories(reference_friction_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/test/support ${ROCKING_SICONOS_INCLUDE}
                               ${ROCKING_SICONOS_INCLUDE}/siconos/numerics ${ROCKING_SICONOS_INCLUDE}/siconos)
    target_link_libraries(reference_friction_tests PRIVATE rocking_monitor_core GTest::gtest_main ${ROCKING_SICONOS_NUMERICS})
    target_compile_definitions(reference_friction_tests PRIVATE ROCKING_RECORDS_DIR="${ROCKING_RECORDS_DIR}")
    target_compile_options(reference_friction_tests PRIVATE -Wall -Wextra)
    gtest_discover_tests(reference_friction_tests TEST_PREFIX "reference_friction." DISCOVERY_TIMEOUT 60
                         PROPERTIES TIMEOUT 600)
  else()
    message(STATUS "rocking_monitor: Siconos numerics not found (libsiconos-numerics-dev): "
                   "reference_friction_tests not built")
  endif()
endif()
