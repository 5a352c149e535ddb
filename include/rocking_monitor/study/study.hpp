#pragma once

// The paper's parametric study (Boroschek & Romo, "Overturning criteria for non-anchored
// non-symmetric rigid bodies", sections "Overturning criteria validation for symmetric bodies" and
// "... for non-symmetric bodies"): every body of a grid against every horizontal record component,
// in both polarities, with and without the vertical component of the same station, compared with
// the screening criteria (Housner eq. 1, Ishiyama eq. 2, Ishiyama with B' = 2 nu B, the 0.2 rule).
//
// ROS-free; the YAML body files and the JSON summary live in rocking_monitor/study/study_io.hpp
// (yaml-cpp and nlohmann-json, linked privately by the study layer); rocking_study is the command
// line over both. Everything is in namespace rocking_monitor::core::study.
//
// This header gathers the study's parts, one job each:
//   study_error.hpp        StudyError, thrown by all of them
//   study_bodies.hpp       the body grid
//   study_records.hpp      loading the records (MANIFEST.csv or a directory scan)
//   study_runner.hpp       the cases, their numbering and shards, running them
//   study_items.hpp        two-plane items on station pairs rotated to azimuths (item_cases.csv)
//   case_table.hpp         writing cases.csv, bodies.csv, records.csv
//   study_summary.hpp      the summary numbers
//   study_report.hpp       the summary as text
//   case_table_reader.hpp  reading cases.csv back (--merge)

#include "rocking_monitor/study/case_table.hpp"
#include "rocking_monitor/study/case_table_reader.hpp"
#include "rocking_monitor/study/study_bodies.hpp"
#include "rocking_monitor/study/study_error.hpp"
#include "rocking_monitor/study/study_items.hpp"
#include "rocking_monitor/study/study_records.hpp"
#include "rocking_monitor/study/study_report.hpp"
#include "rocking_monitor/study/study_runner.hpp"
#include "rocking_monitor/study/study_summary.hpp"
