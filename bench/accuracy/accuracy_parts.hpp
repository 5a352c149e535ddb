#pragma once
// The parts of rocking_accuracy (bench/rocking_accuracy.cpp), one file each in bench/accuracy/.

#include <cstddef>
#include <string>

namespace rocking_monitor::bench::accuracy {

/// work_precision.csv; returns the number of exact-trig batch runs that differ from the scalar run.
int work_precision(const std::string& out_dir, const std::string& records, bool quick, std::size_t batch_lanes);
/// overturn_agreement.csv.
void overturn_agreement(const std::string& out_dir, const std::string& records, int jobs, bool quick);
/// stability_map.csv.
void stability_maps(const std::string& out_dir, int jobs, bool quick);
/// planar_vs_3d.csv: the planar pair against the 3-D model.
void planar_vs_3d(const std::string& out_dir, const std::string& records, bool quick);
/// accuracy_policy.csv and its table; returns 1 when a fast path fails the policy.
int accuracy_policy(const std::string& out_dir, const std::string& records, int jobs, bool quick);

}  // namespace rocking_monitor::bench::accuracy
