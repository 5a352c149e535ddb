# The feeds layer's third-party library: libmseed (Debian libmseed-dev, miniSEED 2) for the SeedLink
# bridge's records. Its gtests are in core_tests (test/feeds/, cmake/rocking_sim.cmake).
find_package(PkgConfig REQUIRED)
pkg_check_modules(ROCKING_MSEED REQUIRED IMPORTED_TARGET mseed)
target_link_libraries(rocking_monitor_feeds PUBLIC PkgConfig::ROCKING_MSEED Threads::Threads)
# OpenSSL's libcrypto (Debian libssl-dev) for the HMAC-SHA256 of authenticated datagrams (issue 52).
find_package(OpenSSL REQUIRED)
target_link_libraries(rocking_monitor_feeds PRIVATE OpenSSL::Crypto)
