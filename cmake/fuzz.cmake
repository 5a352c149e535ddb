# issue 19 part 4: a seeded mutation fuzzer over every record reader (read_record) and the catalogue
# parser, run by scripts/run_sanitizers.sh in a -DROCKING_SANITIZE=ON build (docs/sanitizers.md).
# Built in every build with tests so it never rots; only the sanitizer script runs its long pass.
if(BUILD_TESTING)
  add_executable(fuzz_parsers test/fuzz/fuzz_parsers.cpp test/fuzz/mutator.cpp test/fuzz/seed_records.cpp
                            test/fuzz/network_parsers.cpp
                            test/support/record_writers.cpp)  # the format tests' writers
  target_link_libraries(fuzz_parsers PRIVATE rocking_monitor_core PkgConfig::ROCKING_MSEED)
  target_include_directories(fuzz_parsers PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/test/fuzz ${CMAKE_CURRENT_SOURCE_DIR}/test/support)
  target_compile_options(fuzz_parsers PRIVATE -Wall -Wextra)
  if(ROCKING_SANITIZE)
    target_compile_options(fuzz_parsers PRIVATE ${ROCKING_SANITIZE_FLAGS})
  endif()
endif()
