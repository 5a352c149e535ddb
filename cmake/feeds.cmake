# The feeds layer (issue 18): libmseed (Debian libmseed-dev, miniSEED 2) and its gtests.
find_package(PkgConfig REQUIRED)
pkg_check_modules(ROCKING_MSEED REQUIRED IMPORTED_TARGET mseed)
target_link_libraries(rocking_monitor_feeds PUBLIC PkgConfig::ROCKING_MSEED Threads::Threads)

if(BUILD_TESTING)
  find_package(GTest REQUIRED)
  file(GLOB feeds_tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/test/feeds/*.cpp)
  add_executable(feeds_tests ${feeds_tests})
  target_link_libraries(feeds_tests PRIVATE rocking_monitor_feeds GTest::gtest_main)
  target_include_directories(feeds_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/test/support)
  include(GoogleTest)
  gtest_discover_tests(feeds_tests DISCOVERY_TIMEOUT 60 TEST_PREFIX feeds. PROPERTIES TIMEOUT 120)
endif()
