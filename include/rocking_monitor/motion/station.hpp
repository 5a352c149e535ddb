#pragma once

// Stations: the components (two horizontals, optionally a vertical) recorded at one place in one
// earthquake, grouped from a records directory, loaded together and rotated to any azimuth.
//
// Orientation convention used throughout (and by record_to_bag / ground_motion_player):
//  * An azimuth is in degrees clockwise from north, seen from above: N = 0, E = 90, S = 180, W = 270.
//  * A horizontal component labelled with an azimuth (PEER "090", "228", "N", "-W", BBP "N-S",
//    "E-W", SMC "360") is the ground acceleration along that azimuth, positive toward it.
//  * rotate() returns the ground acceleration `along` a requested azimuth and `left` of it (along
//    azimuth - 90 deg, i.e. 90 deg counter-clockwise seen from above), so (along, left, up) is a
//    right-handed frame like REP 103's (x forward, y left, z up). For along = east, left = north:
//    ENU.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "rocking_monitor/motion/component.hpp"
#include "rocking_monitor/motion/record_reader.hpp"

namespace rocking_monitor::core {

/// Thrown for a malformed manifest, an inconsistent station (three horizontals, unequal dt, ...),
/// an unknown station name or an impossible rotation. what() is one line naming the file (and line)
/// or both files involved.
class StationError : public RecordError {
 public:
  using RecordError::RecordError;
};

/// Azimuth (degrees clockwise from north, in [0, 360)) of a horizontal component from its label:
/// a number ("000", "090", "228", "360", "37.5"), a compass letter ("N", "E", "S", "W", with or
/// without a leading '-' as in PEER file names), or a BBP axis ("N-S" = north, "E-W" = east).
/// Returns nullopt for verticals and for labels that carry no direction ("H", "L", "T", ...).
std::optional<double> label_azimuth_deg(const std::string& label);

/// Label for a rotated component: a whole azimuth as three digits ("090"), otherwise up to 10
/// significant digits ("37.5"). label_azimuth_deg() reads it back.
std::string format_azimuth_label(double azimuth_deg);

/// One component of a station, before it is read.
struct StationComponent {
  std::string file;    ///< path of the file holding it (a BBP file holds three components)
  std::string label;   ///< label as in the manifest or the file name ("090", "W", "N-S", "UP")
  bool vertical = false;
  std::size_t manifest_line = 0;  ///< 1-based line in MANIFEST.csv; 0 when grouped by file name
  double manifest_dt = 0.0;       ///< dt_s from the manifest, s (0 when unknown)
  std::size_t manifest_npts = 0;  ///< npts from the manifest (0 when unknown)
};

/// How a listing grouped the files.
enum class StationSource { Manifest, FileNames, Files };

/// A station: components that belong together. Horizontals are listed in manifest / file order;
/// load_station() orders them (see StationRecord).
struct StationInfo {
  std::string id;       ///< unique, file-name safe: "<event>/<slug of station>", e.g. "northridge_1994/rinaldi_receiving_sta"
  std::string event;    ///< manifest 'event' column (the directory slug, e.g. "northridge_1994"), else the directory name
  std::string station;  ///< manifest 'station' column, else the station code from the file name
  std::vector<StationComponent> horizontals;
  std::vector<StationComponent> verticals;  ///< at most one
  StationSource source = StationSource::Manifest;

  std::size_t component_count() const { return horizontals.size() + verticals.size(); }
};

struct StationListing {
  std::string records_dir;
  StationSource source = StationSource::Manifest;
  std::vector<StationInfo> stations;       ///< manifest order (file-name grouping: sorted by id)
  std::vector<std::string> ignored_files;  ///< files of the directory that are not records (README, ...)
};

struct StationListOptions {
  /// Group by file naming even when MANIFEST.csv exists (used to cross-check the two).
  bool ignore_manifest = false;
};

/// Lists the stations of a records directory.
///  * With `<dir>/MANIFEST.csv` (columns in ../shared/records/README.md; RFC 4180 quoting, so station
///    names may contain commas): one station per distinct (event, station) pair, components in
///    manifest order; `file` is relative to the directory.
///  * Otherwise every file below the directory (recursively) is grouped by its name:
///    `RSN<n>_<EVENT>_<STA><COMP>.AT2` by (directory, n, STA), other AT2 files `<STA><COMP>.AT2` by
///    (directory, STA), where COMP is a 3-digit azimuth, `-N/-E/-S/-W` or `UP/DWN` (with or without
///    '-'); a BBP file is one station with N-S, E-W and U-D; SMC files by the station named in
///    their header; a CSV file is one station (its horizontal and, with 3 columns, its vertical).
///    Files with other extensions are reported in ignored_files.
/// Throws StationError naming the manifest line (bad quoting, missing column, unknown H:/V: prefix,
/// more than two horizontals or one vertical for a station) or the directory (missing).
StationListing list_stations(const std::string& records_dir, const StationListOptions& options = {});

/// An ad-hoc station from 1-3 files (e.g. `--file a.AT2 --file b.AT2 --file up.AT2`, or one BBP or
/// CSV file holding several components). The files are read to learn their components.
/// Throws RecordError/StationError (unreadable file, more than two horizontals, ...).
StationInfo station_from_files(const std::vector<std::string>& files, const ReadOptions& options = {});

/// Finds a station by, in this order: its id, its name or "<event>/<name>" (case-insensitive, exact),
/// the file name of one of its components (e.g. "RSN1063_NORTHR_RRS228.AT2" or "luc.bbp"), or a
/// case-insensitive substring of "<event>/<name>" or id that matches exactly one station.
/// Throws StationError when nothing or several stations match (listing up to 8 candidates).
const StationInfo& find_station(const StationListing& listing, const std::string& query);

/// A station read into memory.
struct StationRecord {
  StationInfo info;
  /// 0-2 horizontal components. With two horizontals whose azimuths are known they are ordered so
  /// that horizontals[1] points counter-clockwise (seen from above) of horizontals[0], 90 deg for an
  /// orthogonal pair: (h0, h1, up) is right-handed and both channels are used unchanged (for N/E:
  /// h0 = E, h1 = N, i.e. ENU). Otherwise the listing order is kept (and a note says so).
  std::vector<Component> horizontals;
  std::optional<Component> vertical;  ///< positive up (readers flip DWN channels)
  /// Things a user should know, one line each: label disagreements between the file name / manifest
  /// and the header (the header wins, e.g. the three Chi-Chi "-E" files whose header says W),
  /// manifest dt/npts that differ from the data, pairs that are not orthogonal.
  std::vector<std::string> notes;
};

/// Reads every component of a station (each file once). Azimuths come from the labels in the file
/// headers. Throws RecordError (unreadable file), StationError (a listed component is not in its
/// file, e.g. a BBP column label that does not exist).
StationRecord load_station(const StationInfo& info, const ReadOptions& options = {});

/// The ground acceleration of a horizontal pair along an azimuth and 90 deg to the left of it.
struct RotatedPair {
  Component along;  ///< along azimuth_deg, positive toward it; label = format_azimuth_label(azimuth)
  Component left;   ///< along azimuth_deg - 90 deg (90 deg counter-clockwise seen from above)
};

/// Rotates two horizontal components (azimuths from their labels) to `azimuth_deg` (degrees
/// clockwise from north; any finite value, taken modulo 360). For an orthogonal pair
///   along = a cos(azimuth - az_a) + b cos(azimuth - az_b),
///   left  = a cos(azimuth - 90 - az_a) + b cos(azimuth - 90 - az_b);
/// cosines of whole multiples of 90 deg are exact (0, +-1), so rotating to a component's own azimuth
/// or by 90/180 deg reproduces, permutes or negates the samples exactly, the vector norm is preserved
/// sample by sample (to rounding) and rotating the result back gives the inputs.
/// A pair that is not orthogonal (Lucerne's sensors are at 260 and 345 deg, 85 deg apart) is resolved
/// exactly instead: the horizontal ground acceleration g solves a = g.u(az_a), b = g.u(az_b) and is
/// projected on the two output directions.
/// Throws StationError naming both files when dt, t0 or the number of samples differ, when a label
/// carries no azimuth, when either is vertical, or when they are less than 10 deg from parallel.
RotatedPair rotate(const Component& a, const Component& b, double azimuth_deg);

/// Lower-case, [a-z0-9_] only, runs of anything else collapsed to one '_' ("Gilroy - Gavilan Coll." ->
/// "gilroy_gavilan_coll").
std::string slugify(const std::string& text);

}  // namespace rocking_monitor::core
