// Cost of the live monitor's core per input sample: every item of a catalogue (ItemMonitor: both
// rocking planes, running spectra and criteria, the adaptive model) stepped on one 3-component
// feed, as RockingMonitor::on_sample does after the ROS part (issue 12: "the node with 10,000
// two-plane items under fidelity adaptive <= 1.5 ms per sample on Kobe Takatori").
//
//   monitor_benchmarks [--benchmark_filter=REGEX] ...
//
// The catalogue is the one scripts/measure_monitor_load.sh gives the node (scripts/make_catalogue.py,
// seed 1: random geometry, mu_s and yaw), or ROCKING_BENCH_CATALOGUE=FILE. The input is Kobe 1995
// Takatori (both horizontals, 100 Hz, 41 s; no vertical record: zero, as in the bag) from ROCKING_RECORDS_DIR, rotated into each
// item's frame by its yaw as tf2 does in the node. ROCKING_BENCH_SAMPLES=N: the batch benchmark on the
// first N samples only (the strongest shaking: N = 600). ROCKING_BENCH_SOLID=3d|planar|auto: which model
// decides items with a 3-D description (a catalogue from make_catalogue.py --solid; default auto, as
// the node's solid_model).
//
// Counters: ms_per_sample (thread CPU time per input sample, all items), ns_per_item_sample,
// allocs_per_sample (must be 0); the batch also deferred_frac (share of item-samples deferred).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "allocation_counter.hpp"
#include "bench_common.hpp"
#include "rocking_monitor/monitoring/catalogue_file.hpp"
#include "rocking_monitor/monitoring/item_monitor.hpp"
#include "rocking_monitor/monitoring/monitor_batch.hpp"
#include "rocking_monitor/monitoring/state_snapshot.hpp"
#include "rocking_monitor/motion/station.hpp"

namespace rb = rocking_monitor::bench;
using namespace rocking_monitor::core;

namespace {

struct Feed {
  std::vector<double> e, n, up;  // m/s^2, sensor frame (x east-ish, y north-ish, z up)
  double dt = 0.0;
};

struct Case {
  std::vector<CatalogueItem> items;
  Feed feed;
  std::vector<double> cos_yaw, sin_yaw;
};

std::unique_ptr<Case> g_case;

std::string catalogue_path(std::size_t n, bool single_plane) {
  if (const char* env = std::getenv("ROCKING_BENCH_CATALOGUE")) return env;
  const std::string out = "/tmp/rocking_monitor_bench_catalogue_" + std::to_string(n) +
                          (single_plane ? "_1" : "_2") + ".yaml";
  const std::string cmd = "/usr/bin/python3 " ROCKING_SOURCE_DIR "/scripts/make_catalogue.py " +
                          std::to_string(n) + " " + out + (single_plane ? " --single-plane" : "");
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("monitor_benchmarks: '" + cmd + "' failed");
  return out;
}

Feed load_takatori(const std::string& dir) {
  const StationListing listing = list_stations(dir);
  const StationRecord st = load_station(find_station(listing, "RSN1120_KOBE_TAK000.AT2"));
  // Takatori has no vertical record here: the vertical input is then zero (as in the bag).
  if (st.horizontals.size() != 2) throw std::runtime_error("Takatori: 2 horizontal components expected");
  Feed f;
  f.dt = st.horizontals[0].dt;
  std::size_t n = std::min(st.horizontals[0].accel.size(), st.horizontals[1].accel.size());
  if (st.vertical) n = std::min(n, st.vertical->accel.size());
  f.e.assign(st.horizontals[0].accel.begin(), st.horizontals[0].accel.begin() + n);
  f.n.assign(st.horizontals[1].accel.begin(), st.horizontals[1].accel.begin() + n);
  if (st.vertical) f.up.assign(st.vertical->accel.begin(), st.vertical->accel.begin() + n);
  else f.up.assign(n, 0.0);
  return f;
}

SolidChoice g_solid = SolidChoice::Auto;  // ROCKING_BENCH_SOLID, read once in main()

ItemMonitor::Options options() {
  ItemMonitor::Options o;  // the node's defaults: adaptive, dopri5 tol 1e-8
  o.fidelity = Fidelity::Adaptive;
  o.solid = g_solid;
  return o;
}

// Input samples the batch benchmarks step: the whole record, or its first ROCKING_BENCH_SAMPLES (the
// strongest shaking is within the first 800: profile it alone).
std::size_t samples(const Case& c) {
  const std::size_t all = c.feed.e.size();
  const char* env = std::getenv("ROCKING_BENCH_SAMPLES");
  return env != nullptr ? std::clamp<std::size_t>(std::strtoul(env, nullptr, 10), 2, all) : all;
}

// Item frame input: R(item <- sensor) = Rz(-yaw).
inline void item_input(const Case& c, std::size_t k, std::size_t i, double& ax, double& ay) {
  ax = c.cos_yaw[k] * c.feed.e[i] + c.sin_yaw[k] * c.feed.n[i];
  ay = -c.sin_yaw[k] * c.feed.e[i] + c.cos_yaw[k] * c.feed.n[i];
}

void finish(benchmark::State& state, double seconds, double samples, double items, double allocs) {
  state.counters["ms_per_sample"] = 1e3 * seconds / samples;
  state.counters["ns_per_item_sample"] = 1e9 * seconds / (samples * items);
  state.counters["allocs_per_sample"] = allocs / samples;
  state.counters["items"] = items;
}

// Today's node: one ItemMonitor per item, stepped one after another.
void BM_ItemMonitors(benchmark::State& state) {
  const Case& c = *g_case;
  std::vector<std::unique_ptr<ItemMonitor>> items;
  for (const CatalogueItem& it : c.items) items.push_back(std::make_unique<ItemMonitor>(it.spec, options()));
  const std::size_t n = c.feed.e.size();
  double seconds = 0, samples = 0, allocs = 0;
  for (auto _ : state) {
    for (std::size_t k = 0; k < items.size(); ++k) {
      double ax, ay;
      item_input(c, k, 0, ax, ay);
      items[k]->start(0.0, ax, ay, c.feed.up[0], c.feed.dt);
    }
    const long a0 = rocking_monitor::testing::allocation_count();
    const double t0 = rb::thread_cpu_seconds();
    for (std::size_t i = 1; i < n; ++i) {
      for (std::size_t k = 0; k < items.size(); ++k) {
        double ax, ay;
        item_input(c, k, i, ax, ay);
        items[k]->step(ax, ay, c.feed.up[i], c.feed.dt);
      }
    }
    seconds += rb::thread_cpu_seconds() - t0;
    allocs += static_cast<double>(rocking_monitor::testing::allocation_count() - a0);
    samples += static_cast<double>(n - 1);
  }
  finish(state, seconds, samples, static_cast<double>(items.size()), allocs);
}

// The batch benchmarks' items and their inputs: every item's sample i rotated into its frame, as the
// node does (ax, ay, az per item, m/s^2); fill() over a range of items (a thread's share).
struct BatchFeed {
  const Case& c;
  std::vector<std::unique_ptr<ItemMonitor>> items;
  std::vector<double> ax, ay, az;
  explicit BatchFeed(const Case& cc) : c(cc), ax(cc.items.size()), ay(cc.items.size()), az(cc.items.size()) {
    for (const CatalogueItem& it : c.items) items.push_back(std::make_unique<ItemMonitor>(it.spec, options()));
  }
  std::size_t size() const { return items.size(); }
  void fill(std::size_t i, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      item_input(c, k, i, ax[k], ay[k]);
      az[k] = c.feed.up[i];
    }
  }
  void fill(std::size_t i) { fill(i, 0, size()); }
  /// Every item started on sample 0: the batch's item list.
  std::vector<ItemMonitor*> start() {
    fill(0);
    std::vector<ItemMonitor*> ptrs;
    for (std::size_t k = 0; k < size(); ++k) {
      items[k]->start(0.0, ax[k], ay[k], az[k], c.feed.dt);
      ptrs.push_back(items[k].get());
    }
    return ptrs;
  }
};

// The batch (monitoring/monitor_batch.hpp): the same items, quiet samples deferred. Counter
// deferred_frac: share of item-samples deferred.
void BM_MonitorBatch(benchmark::State& state) {
  const Case& c = *g_case;
  BatchFeed f(c);
  const std::size_t n = samples(c), m = f.size();
  double seconds = 0, samples = 0, allocs = 0, deferred = 0, planes = 0;
  for (auto _ : state) {
    MonitorBatch batch(f.start());
    const long a0 = rocking_monitor::testing::allocation_count();
    const double t0 = rb::thread_cpu_seconds();
    for (std::size_t i = 1; i < n; ++i) {
      f.fill(i);  // as the node: each item's input rotated into its frame
      deferred += static_cast<double>(batch.step(0, m, f.ax.data(), f.ay.data(), f.az.data(), c.feed.dt));
      planes += static_cast<double>(m);
    }
    seconds += rb::thread_cpu_seconds() - t0;
    allocs += static_cast<double>(rocking_monitor::testing::allocation_count() - a0);
    samples += static_cast<double>(n - 1);
  }
  finish(state, seconds, samples, static_cast<double>(m), allocs);
  state.counters["deferred_frac"] = deferred / planes;
}

// All the cores (issue 28 part 5): the batch stepped as the node does with ~threads (TBB arena,
// parallel_for over ranges of 32 items, each range rotating its items' inputs and stepping them).
// Counters: wall_ms_per_sample (wall clock: what bounds the lag), cpu_ms_per_sample (all threads,
// CLOCK_PROCESS_CPUTIME_ID), threads; results do not depend on the thread count (test_monitor_batch).
void BM_MonitorBatchThreads(benchmark::State& state, int threads) {
  const Case& c = *g_case;
  BatchFeed f(c);
  const std::size_t n = samples(c), m = f.size();
  double wall = 0, cpu = 0, samples = 0;
  tbb::task_arena arena(threads);
  for (auto _ : state) {
    MonitorBatch batch(f.start());
    const double c0 = rb::process_cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 1; i < n; ++i) {
      auto range = [&](std::size_t b, std::size_t e) {
        f.fill(i, b, e);
        batch.step(b, e, f.ax.data(), f.ay.data(), f.az.data(), c.feed.dt);
      };
      if (threads == 1) {
        range(0, m);
      } else {
        arena.execute([&] {
          tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m, 32),
                            [&](const tbb::blocked_range<std::size_t>& r) { range(r.begin(), r.end()); });
        });
      }
    }
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    cpu += rb::process_cpu_seconds() - c0;
    samples += static_cast<double>(n - 1);
  }
  state.counters["wall_ms_per_sample"] = 1e3 * wall / samples;
  state.counters["cpu_ms_per_sample"] = 1e3 * cpu / samples;
  state.counters["threads"] = threads;
  state.counters["items"] = static_cast<double>(m);
}

// State snapshots (issue 29): the batch stepped into the strong motion, then every 10th sample (0.1 s
// at 100 Hz: the node's default ~snapshot_period) all items synced and encoded into one buffer, as
// RockingMonitor::take_snapshot does between samples. Counters: snapshot_bytes, encode_ms (sync +
// encode, on the sample thread), ms_per_sample (encode_ms / 10: its cost per input sample at that
// period), allocs_per_snapshot (after the first: must be 0); seal_ms (the checksums) and write_ms
// (write + fsync + rename to /tmp) are the writer thread's, off the sample path.
void BM_StateSnapshot(benchmark::State& state) {
  const Case& c = *g_case;
  BatchFeed f(c);
  std::vector<std::unique_ptr<ItemMonitor>>& items = f.items;
  const std::size_t n = c.feed.e.size(), m = f.size(), every = 10;
  const std::size_t from = n / 4, to = std::min(n, from + 400);  // Takatori's strong motion: ~10-14 s
  SnapshotEncoder enc;
  std::vector<std::uint8_t> buf;
  double encode_s = 0, seal_s = 0, write_s = 0, snapshots = 0, allocs = 0, bytes = 0, moving = 0;
  const std::string path = "/tmp/rocking_monitor_bench_" + std::to_string(::getpid()) + ".snapshot";
  for (auto _ : state) {
    MonitorBatch batch(f.start());
    bool warm = false;  // the first snapshot grows the buffers; the next ones must not allocate
    for (std::size_t i = 1; i < to; ++i) {
      f.fill(i);
      batch.step(0, m, f.ax.data(), f.ay.data(), f.az.data(), c.feed.dt);
      if (i < from || i % every != 0) continue;
      const long a0 = rocking_monitor::testing::allocation_count();
      const double t0 = rb::thread_cpu_seconds();
      batch.sync_all();
      enc.begin(buf, 1, 0.0, 1, m);
      SnapshotSensor sensor;
      sensor.name = "floor";
      enc.sensor(sensor);
      for (std::size_t k = 0; k < m; ++k) enc.item(c.items[k].spec.id, *items[k], nullptr);
      enc.finish(false);
      const double t1 = rb::thread_cpu_seconds();
      if (warm) {
        encode_s += t1 - t0;
        allocs += static_cast<double>(rocking_monitor::testing::allocation_count() - a0);
        snapshots += 1;
        seal_snapshot(buf);
        const double t2 = rb::thread_cpu_seconds();
        seal_s += t2 - t1;
        const auto w0 = std::chrono::steady_clock::now();
        if (const std::string e = write_file_durably(path, buf.data(), buf.size()); !e.empty())
          state.SkipWithError(e.c_str());
        write_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
        bytes = static_cast<double>(buf.size());
        for (const auto& im : items) moving += im->mode() != ItemMode::Rest;
      }
      warm = true;
    }
  }
  std::remove(path.c_str());
  state.counters["items"] = static_cast<double>(m);
  state.counters["snapshot_bytes"] = bytes;
  state.counters["encode_ms"] = 1e3 * encode_s / snapshots;
  state.counters["ms_per_sample"] = 1e3 * encode_s / snapshots / static_cast<double>(every);
  state.counters["allocs_per_snapshot"] = allocs / snapshots;
  state.counters["seal_ms"] = 1e3 * seal_s / snapshots;
  state.counters["write_ms"] = 1e3 * write_s / snapshots;
  state.counters["items_moving_frac"] = moving / (snapshots * static_cast<double>(m));
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  const std::string dir = rb::records_dir();
  if (!rb::records_available(dir)) {
    std::fprintf(stderr, "monitor_benchmarks: records folder %s not found (set ROCKING_RECORDS_DIR)\n", dir.c_str());
    return 0;
  }
  const char* solid = std::getenv("ROCKING_BENCH_SOLID");
  if (solid != nullptr && !parse_solid_choice(solid, g_solid)) {
    std::fprintf(stderr, "monitor_benchmarks: ROCKING_BENCH_SOLID must be 3d, planar or auto, not '%s'\n", solid);
    return 1;
  }
  const std::size_t n_items = std::getenv("ROCKING_BENCH_ITEMS") ? std::stoul(std::getenv("ROCKING_BENCH_ITEMS")) : 10000;
  g_case = std::make_unique<Case>();
  g_case->items = load_catalogue_items_file(catalogue_path(n_items, false));
  g_case->feed = load_takatori(dir);
  for (const CatalogueItem& it : g_case->items) {
    g_case->cos_yaw.push_back(std::cos(it.pose.yaw));
    g_case->sin_yaw.push_back(std::sin(it.pose.yaw));
  }
  const std::string tag = "monitor/takatori/" + std::to_string(g_case->items.size()) + "_two_plane/adaptive" +
                          (solid != nullptr ? std::string("/solid:") + solid : std::string());
  benchmark::RegisterBenchmark((tag + "/item_monitors").c_str(), BM_ItemMonitors)->Unit(benchmark::kMillisecond)->Iterations(1);
  benchmark::RegisterBenchmark((tag + "/batch").c_str(), BM_MonitorBatch)->Unit(benchmark::kMillisecond)->Iterations(1);
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  std::vector<int> counts{1, 2};
  if (cores > 2) counts.push_back(cores);  // 1, 2 and all cores
  for (int threads : counts) {
    benchmark::RegisterBenchmark((tag + "/batch_threads:" + std::to_string(threads)).c_str(), BM_MonitorBatchThreads, threads)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->UseRealTime();
  }
  benchmark::RegisterBenchmark((tag + "/state_snapshot").c_str(), BM_StateSnapshot)->Unit(benchmark::kMillisecond)->Iterations(1);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
