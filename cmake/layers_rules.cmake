# Which core layer may include (and link) which: the one list of rules, read by cmake/layers.cmake
# (link lines) and cmake/check_layers.cmake (include check). Lowest layer first.
set(ROCKING_LAYER_ALLOWS_physics "")
set(ROCKING_LAYER_ALLOWS_integrate physics)
set(ROCKING_LAYER_ALLOWS_model integrate physics)
set(ROCKING_LAYER_ALLOWS_csv "")
set(ROCKING_LAYER_ALLOWS_motion csv)
set(ROCKING_LAYER_ALLOWS_monitoring model integrate physics motion csv)
set(ROCKING_LAYER_ALLOWS_study monitoring model integrate physics motion csv)
# feeds: live instrument streams (UDP shaking-table datagrams, the SeedLink client, miniSEED decoding,
# channel merging), ROS-free; uses nothing below. Its third-party libraries: cmake/feeds.cmake.
set(ROCKING_LAYER_ALLOWS_feeds "")
# notify: the alarm notifier's core (issue 44): routing, outbox, grouping, SMTP/HTTP/MQTT channels; uses
# monitoring's AlarmDedup (one alarm however many monitors raised it). Libraries: cmake/notify.cmake.
set(ROCKING_LAYER_ALLOWS_notify monitoring model integrate physics motion csv)
set(ROCKING_CORE_LAYER_NAMES physics integrate model csv motion monitoring study feeds notify)

