#pragma once

// Private to src/motion/station_*.cpp: what the station files share. Not part of the public API
// (include/rocking_monitor/motion/station.hpp).

#include <cstddef>
#include <string>
#include <vector>

#include "rocking_monitor/motion/station.hpp"

namespace rocking_monitor::core::station_io {

// ------------------------------------------------------------------ text and errors (station_common.cpp)

std::string upper(std::string s);
std::string lower(std::string s);
std::string trim(const std::string& s);
/// Upper case, trimmed, without a leading '-' / '_' (PEER file names write "-N", "-UP").
std::string normalised_label(const std::string& label);
std::string base_name(const std::string& path);
std::string squote(const std::string& s);
/// Throws StationError "<where>:<line>: <problem>" (line == 0: "<where>: <problem>").
[[noreturn]] void fail(const std::string& where, std::size_t line, const std::string& problem);
std::string read_text_file(const std::string& path);
bool parse_double(const std::string& s, double& out);
bool parse_size(const std::string& s, std::size_t& out);

// ------------------------------------------------------------------ azimuths (station_common.cpp)

/// cos of an angle in degrees; exact (0, +-1) at whole multiples of 90 deg.
double cos_deg(double deg);
std::string deg_text(double deg);
/// Two horizontals closer than this (or to anti-parallel) cannot resolve the horizontal motion.
inline constexpr double kMinSeparationDeg = 10.0;
double normalise_azimuth(double deg);
/// Smallest angle between two azimuths, degrees in [0, 180].
double azimuth_difference(double a, double b);
/// Same component: same azimuth when both labels name one, else the same normalised text.
bool same_label(const std::string& a, const std::string& b);

// ------------------------------------------------------------------ building a listing (station_common.cpp)

/// Assigns unique ids "<event>/<slug>" (a suffix _2, _3, ... on collisions, in listing order).
void assign_ids(std::vector<StationInfo>& stations);
/// Adds a component to its station; duplicates and too many components are errors naming `where`.
void add_component(StationInfo& st, StationComponent c, const std::string& where);

// ------------------------------------------------------------------ the two ways to list

StationListing list_from_manifest(const std::string& dir, const std::string& manifest);  // station_manifest.cpp
StationListing list_from_file_names(const std::string& dir);                            // station_file_names.cpp

}  // namespace rocking_monitor::core::station_io
