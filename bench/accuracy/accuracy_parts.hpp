#pragma once
// The parts of rocking_accuracy (bench/rocking_accuracy.cpp), one file each in bench/accuracy/.

#include <cstddef>
#include <string>

// quiet: no progress display on a terminal (there is none off one: progress_meter.hpp). work-precision
// and planar-vs-3d, serial, say each case they finish instead.

namespace rocking_monitor::bench::accuracy {

/// work_precision.csv; returns the number of exact-trig batch runs that differ from the scalar run.
int work_precision(const std::string& out_dir, const std::string& records, bool quick, std::size_t batch_lanes);
/// overturn_agreement.csv.
void overturn_agreement(const std::string& out_dir, const std::string& records, int jobs, bool quick, bool quiet);
/// stability_map.csv.
void stability_maps(const std::string& out_dir, int jobs, bool quick, bool quiet);
/// planar_vs_3d.csv: the planar pair against the 3-D model.
void planar_vs_3d(const std::string& out_dir, const std::string& records, bool quick);
/// accuracy_policy.csv and its table; returns 1 when a fast path fails the policy.
int accuracy_policy(const std::string& out_dir, const std::string& records, int jobs, bool quick, bool quiet);

}  // namespace rocking_monitor::bench::accuracy
