# Which core layer may include (and link) which: the one list of rules, read by cmake/layers.cmake
# (link lines) and cmake/check_layers.cmake (include check). Lowest layer first.
set(ROCKING_LAYER_ALLOWS_physics "")
set(ROCKING_LAYER_ALLOWS_integrate physics)
set(ROCKING_LAYER_ALLOWS_model integrate physics)
set(ROCKING_LAYER_ALLOWS_csv "")
set(ROCKING_LAYER_ALLOWS_motion csv)
set(ROCKING_LAYER_ALLOWS_monitoring model integrate physics motion csv)
set(ROCKING_LAYER_ALLOWS_study model integrate physics motion csv)
set(ROCKING_CORE_LAYER_NAMES physics integrate model csv motion monitoring study)

# --- feeds (issue 18): live instrument feeds (SeedLink client, miniSEED decoding, channel merging);
# uses no other layer. Its third-party libraries are linked by cmake/feeds.cmake.
set(ROCKING_LAYER_ALLOWS_feeds "")
list(APPEND ROCKING_CORE_LAYER_NAMES feeds)
