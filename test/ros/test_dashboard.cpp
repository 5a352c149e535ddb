// rostest: the dashboard during the pulse replay. Its HTTP endpoints against what this test receives
// from the monitor on ROS: the page, the snapshot (every catalogue item, each item's mode equal to the
// last ~states), and the SSE stream (every alarm within 200 ms of its arrival on ROS).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <regex>
#include <set>
#include <thread>
#include <vector>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <ros/ros.h>

#include "rocking_monitor/OverturnAlarm.h"
#include "rocking_monitor/RockingStateArray.h"
#include "rocking_monitor/ros/catalogue.hpp"

// After the project's headers: httplib's <resolv.h> defines `_res`, which breaks Eigen's headers.
#include <httplib.h>

namespace rocking_monitor::test {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

const char* mode_name(std::uint8_t m) {
  static const char* names[] = {"REST", "ROCKING", "BEYOND_TIPPING", "COMMITTED", "OVERTURNED"};
  return m < 5 ? names[m] : "UNKNOWN";
}

// "http://127.0.0.1:PORT/" -> host, port
bool split_url(const std::string& url, std::string& host, int& port) {
  const std::string prefix = "http://";
  if (url.compare(0, prefix.size(), prefix) != 0) return false;
  const auto colon = url.find(':', prefix.size());
  if (colon == std::string::npos) return false;
  host = url.substr(prefix.size(), colon - prefix.size());
  port = std::stoi(url.substr(colon + 1));
  return port > 0;
}

// Reads /api/events on its own thread; records when each alarm arrives.
class EventReader {
 public:
  EventReader(const std::string& host, int port) : client_(host, port) {
    client_.set_read_timeout(std::chrono::seconds(5));  // keep-alives come every second
    thread_ = std::thread([this] { run(); });
  }
  ~EventReader() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  bool connected() const { return connected_; }
  std::map<std::string, Clock::time_point> alarms() {
    std::lock_guard<std::mutex> lock(mutex_);
    return alarms_;
  }
  int state_events() const { return state_events_; }

 private:
  void run() {
    std::string buffer;
    client_.Get("/api/events", [&](const char* data, std::size_t n) {
      const auto now = Clock::now();
      connected_ = true;
      buffer.append(data, n);
      for (std::size_t end; (end = buffer.find("\n\n")) != std::string::npos;) {
        const std::string frame = buffer.substr(0, end);
        buffer.erase(0, end + 2);
        std::string event, payload;
        std::size_t pos = 0;
        while (pos < frame.size()) {
          const std::size_t nl = std::min(frame.find('\n', pos), frame.size());
          const std::string line = frame.substr(pos, nl - pos);
          if (line.rfind("event: ", 0) == 0) event = line.substr(7);
          if (line.rfind("data: ", 0) == 0) payload = line.substr(6);
          pos = nl + 1;
        }
        if (event == "states") ++state_events_;
        if (event == "alarm") {
          const json a = json::parse(payload);
          std::lock_guard<std::mutex> lock(mutex_);
          alarms_.emplace(a.at("item").get<std::string>() + "/" + a.at("level").get<std::string>(), now);
        }
      }
      return !stop_;
    });
  }
  httplib::Client client_;
  std::thread thread_;
  std::atomic<bool> stop_{false}, connected_{false};
  std::atomic<int> state_events_{0};
  std::mutex mutex_;
  std::map<std::string, Clock::time_point> alarms_;
};

// The page's scripts are ES modules (src/ros/dashboard_web/): index.html loads the entry with
// <script type="module">, and each module the entry and the others import ("from './x.js'") must be
// served by the node, 200, as JavaScript (a browser refuses a module of another type). Returns the
// paths fetched.
std::set<std::string> check_page_modules(httplib::Client& http, const std::string& page) {
  const std::regex entry(R"re(<script type="module" src="(/\w+\.js)"></script>)re");
  const std::regex import(R"re(from '\./(\w+\.js)')re");
  std::smatch m;
  std::vector<std::string> todo;
  if (std::regex_search(page, m, entry))
    todo.push_back(m[1]);
  else
    ADD_FAILURE() << "no <script type=\"module\"> in the page";
  std::set<std::string> seen;
  while (!todo.empty()) {
    const std::string path = todo.back();
    todo.pop_back();
    if (!seen.insert(path).second) continue;
    auto r = http.Get(path.c_str());
    if (!r) {
      ADD_FAILURE() << path << ": no answer";
      continue;
    }
    EXPECT_EQ(r->status, 200) << path;
    const std::string type = r->get_header_value("Content-Type");
    EXPECT_EQ(type.rfind("application/javascript", 0), 0u) << path << ": " << type;
    EXPECT_GT(r->body.size(), 100u) << path;
    for (std::sregex_iterator it(r->body.begin(), r->body.end(), import), end; it != end; ++it)
      todo.push_back("/" + (*it)[1].str());
  }
  return seen;
}

TEST(Dashboard, ServesThePageTheSnapshotAndTheAlarms) {
  ros::NodeHandle nh, pnh("~");
  std::string ns = "/rocking_monitor", url_param = "/dashboard/url", must_overturn, must_survive;
  pnh.getParam("monitor", ns);
  pnh.getParam("url_param", url_param);
  pnh.getParam("must_overturn", must_overturn);
  pnh.getParam("must_survive", must_survive);
  int min_ensembles = 0;        // items with uncertain parameters the catalogue has (P(overturned) checked)
  double input_peak_x = 0.0;    // the input's peak |a_x|, m/s^2 (0: not checked)
  pnh.getParam("min_ensembles", min_ensembles);
  pnh.getParam("input_peak_x", input_peak_x);

  // The monitor's ROS outputs, as this test receives them.
  std::mutex mutex;
  RockingStateArray::ConstPtr last_states;
  Clock::time_point last_states_time = Clock::now();
  std::map<std::string, Clock::time_point> ros_alarms;
  auto sub_s = nh.subscribe<RockingStateArray>(ns + "/states", 100, [&](const RockingStateArray::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    last_states = m;
    last_states_time = Clock::now();
  });
  auto sub_a = nh.subscribe<OverturnAlarm>(ns + "/alarms", 1000, [&](const OverturnAlarm::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    ros_alarms.emplace(m->item_id + "/" + mode_name(m->level), Clock::now());
  });
  // Callbacks on their own thread: arrival times are not delayed by this test's waits.
  ros::AsyncSpinner spinner(1);
  spinner.start();

  std::string url, host;
  int port = 0;
  const auto start = Clock::now();
  while (!nh.getParam(url_param, url) && Clock::now() - start < std::chrono::seconds(20))
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(split_url(url, host, port)) << "no dashboard URL in " << url_param << ": '" << url << "'";
  std::printf("dashboard at %s\n", url.c_str());

  EventReader events(host, port);
  httplib::Client http(host, port);
  http.set_read_timeout(std::chrono::seconds(10));

  // The page, with its canvas and its script, all from the node.
  auto page = http.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<canvas"), std::string::npos);
  {
    auto r = http.Get("/style.css");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200);
    EXPECT_GT(r->body.size(), 100u);
  }
  // The entry app.js, state.js and the four panels' modules (floor plan, item view, alarm log, health).
  const std::set<std::string> modules = check_page_modules(http, page->body);
  EXPECT_EQ(modules.size(), 6u);
  std::printf("page modules served: %zu\n", modules.size());
  auto missing = http.Get("/nothing_here");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);

  // Every catalogue item is in the snapshot, with its geometry and pose.
  XmlRpc::XmlRpcValue sensors, items;
  ASSERT_TRUE(nh.getParam(ns + "/sensors", sensors) && nh.getParam(ns + "/items", items));
  const live::Catalogue catalogue = live::parse_catalogue(sensors, items);
  {
    auto r = http.Get("/api/snapshot");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200);
    const json snap = json::parse(r->body);
    ASSERT_EQ(snap.at("items").size(), catalogue.items.size());
    for (std::size_t i = 0; i < catalogue.items.size(); ++i) {
      const json& it = snap["items"][i];
      EXPECT_EQ(it.at("id"), catalogue.items[i].spec.id);
      EXPECT_EQ(it.at("width").get<double>(), catalogue.items[i].spec.body.width);
      ASSERT_TRUE(it.contains("pose")) << it.at("id");
      EXPECT_EQ(it["pose"].at("x").get<double>(), catalogue.items[i].pose.x);
      EXPECT_EQ(it["pose"].at("yaw").get<double>(), catalogue.items[i].pose.yaw);
    }
  }
  const auto connect_deadline = Clock::now() + std::chrono::seconds(5);
  while (!events.connected() && Clock::now() < connect_deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(events.connected()) << "no SSE stream";

  // The replay: wait for the overturn, then for the states to stop (bag over).
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  for (;;) {
    ASSERT_LT(Clock::now(), deadline) << "replay did not end";
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    std::lock_guard<std::mutex> lock(mutex);
    if (last_states && ros_alarms.count(must_overturn + "/OVERTURNED") &&
        Clock::now() - last_states_time > std::chrono::seconds(2))
      break;
  }
  // The last SSE frames: until every alarm seen on ROS is on the stream too (a condition; gives up
  // after 30 s, and the check below names the missing one).
  {
    std::set<std::string> keys;
    {
      std::lock_guard<std::mutex> lock(mutex);
      for (const auto& [key, t] : ros_alarms) keys.insert(key);
    }
    const auto sse_deadline = Clock::now() + std::chrono::seconds(30);
    auto all_on_sse = [&] {
      const auto on_sse = events.alarms();
      for (const auto& k : keys)
        if (!on_sse.count(k)) return false;
      return true;
    };
    while (!all_on_sse() && Clock::now() < sse_deadline) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }

  // The snapshot after the replay equals the last ~states, item by item.
  const auto t0 = Clock::now();
  auto r = http.Get("/api/snapshot");
  const double fetch_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200);
  const json snap = json::parse(r->body);
  std::printf("snapshot: %zu bytes, %zu items, fetched and served in %.2f ms\n", r->body.size(),
              snap["items"].size(), fetch_ms);
  RockingStateArray::ConstPtr states;
  std::map<std::string, Clock::time_point> on_ros;
  {
    std::lock_guard<std::mutex> lock(mutex);
    states = last_states;
    on_ros = ros_alarms;
  }
  ASSERT_EQ(snap["items"].size(), states->items.size());
  std::map<std::string, std::string> mode_of;
  int ensembles = 0;
  for (const RockingState& s : states->items) {
    const json* found = nullptr;
    for (const json& it : snap["items"])
      if (it.at("id") == s.id) found = &it;
    ASSERT_NE(found, nullptr) << s.id;
    ASSERT_TRUE(found->contains("state")) << s.id;
    const json& st = (*found)["state"];
    EXPECT_EQ(st.at("mode").get<std::string>(), mode_name(s.mode)) << s.id;
    EXPECT_EQ(st.at("plane").get<std::string>(), s.plane) << s.id;
    EXPECT_EQ(st.at("theta").get<double>(), s.theta) << s.id;  // same message, round-trip doubles
    EXPECT_EQ(st.at("x").at("theta").get<double>(), s.x.theta) << s.id;
    if (s.ensemble_size > 0) {  // P(overturned) over the item's members, as the monitor published it
      ++ensembles;
      EXPECT_EQ(st.at("p_overturned").get<double>(), s.p_overturned.probability) << s.id;
      EXPECT_EQ(st.at("p_overturned_interval")[1].get<double>(), s.p_overturned.upper) << s.id;
    } else {
      EXPECT_FALSE(st.contains("p_overturned")) << s.id;
    }
    mode_of[s.id] = mode_name(s.mode);
  }
  EXPECT_EQ(ensembles, min_ensembles);
  EXPECT_EQ(mode_of[must_overturn], "OVERTURNED");
  EXPECT_NE(mode_of[must_survive], "OVERTURNED");
  EXPECT_NE(mode_of[must_survive], "");

  // The input chart's 60 s: the dashboard's own subscription to the monitor's sensor keeps the peak.
  if (input_peak_x > 0.0) {
    auto in = http.Get("/api/input");
    ASSERT_TRUE(in);
    const json j = json::parse(in->body);
    EXPECT_EQ(j.at("topic"), "/ground/imu");
    ASSERT_FALSE(j.at("points").empty());
    double peak = 0.0;
    for (const json& p : j["points"]) peak = std::max(peak, std::abs(p[1].get<double>()));
    EXPECT_NEAR(peak, input_peak_x, 1e-6) << "the 50 ms bins keep each bin's largest sample";
    std::printf("input chart: %zu points, peak |a_x| %.6f m/s^2\n", j["points"].size(), peak);
  }

  // The alarm log: every alarm the monitor published, newest first.
  ASSERT_EQ(snap.at("alarms").size(), on_ros.size());
  for (std::size_t i = 1; i < snap["alarms"].size(); ++i)
    EXPECT_GE(snap["alarms"][i - 1].at("stamp").get<double>(), snap["alarms"][i].at("stamp").get<double>());
  EXPECT_FALSE(snap.at("health").empty()) << "no sensor health from /diagnostics";

  // One item in full (the page's detail panel), as in the snapshot; unknown ids are 404.
  {
    auto item = http.Get(("/api/item?id=" + must_overturn).c_str());
    ASSERT_TRUE(item);
    ASSERT_EQ(item->status, 200);
    const json j = json::parse(item->body);
    EXPECT_EQ(j.at("state").at("mode"), "OVERTURNED");
    EXPECT_TRUE(j["state"].contains("y"));
    EXPECT_EQ(http.Get("/api/item?id=no_such_item")->status, 404);
  }

  // The chart's 60 s of the overturned item, kept by the server for pages opened after the alarm.
  {
    auto h = http.Get(("/api/history?id=" + must_overturn).c_str());
    ASSERT_TRUE(h);
    const json hist = json::parse(h->body);
    ASSERT_FALSE(hist.at("points").empty());
    EXPECT_LT(hist["points"].back()[2].get<double>(), 0.0) << "an overturned item's energy margin is < 0";
    EXPECT_TRUE(json::parse(http.Get("/api/history?id=no_such_item")->body).at("points").empty());
  }

  // Every alarm on the SSE stream too. Its delay after the arrival here on ROS is printed, a measurement
  // (about a millisecond on a quiet machine), not a verdict: a loaded machine may take longer (issue 42).
  const auto on_sse = events.alarms();
  for (const auto& [key, t_ros] : on_ros) {
    const auto it = on_sse.find(key);
    ASSERT_NE(it, on_sse.end()) << key << " never came on /api/events";
    const double latency_ms = std::chrono::duration<double, std::milli>(it->second - t_ros).count();
    std::printf("alarm %-28s SSE - ROS arrival: %+.2f ms\n", key.c_str(), latency_ms);
  }
  EXPECT_GT(events.state_events(), 0);

  // Issue 19: a dashboard started after the event, with no monitor to listen to, shows the same alarms
  // from the monitor's journal alone (its ~monitor names no running monitor).
  std::string journal;
  if (pnh.getParam("journal", journal)) {
    // The dashboard executable sits beside this test's (devel/lib/rocking_monitor).
    const std::string exe = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "dashboard";
    const std::string journal_arg = "_journal:=" + journal;
    const pid_t pid = fork();
    if (pid == 0) {
      execl(exe.c_str(), exe.c_str(), "__name:=dashboard_late", "_port:=0", "_monitor:=/no_monitor_here",
            journal_arg.c_str(), "_journal_window:=1000000000000.0", nullptr);
      _exit(127);
    }
    ASSERT_GT(pid, 0);
    std::string late_url, late_host;
    int late_port = 0;
    const auto t0 = Clock::now();
    while (!nh.getParam("/dashboard_late/url", late_url) && Clock::now() - t0 < std::chrono::seconds(30))
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::set<std::string> late_alarms, ros_keys;
    if (split_url(late_url, late_host, late_port)) {
      httplib::Client late(late_host, late_port);
      late.set_read_timeout(std::chrono::seconds(10));
      auto r = late.Get("/api/snapshot");
      std::printf("late dashboard at %s: snapshot %s\n", late_url.c_str(),
                  r ? (std::to_string(r->status) + ", " + std::to_string(r->body.size()) + " bytes").c_str()
                    : httplib::to_string(r.error()).c_str());
      if (r && r->status == 200) {
        const json snap_late = json::parse(r->body);
        for (const json& a : snap_late.at("alarms"))
          late_alarms.insert(a.at("item").get<std::string>() + "/" + a.at("level").get<std::string>());
      }
    }
    kill(pid, SIGINT);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_FALSE(late_url.empty()) << "the late dashboard did not start";
    for (const auto& [key, t] : on_ros) ros_keys.insert(key);
    EXPECT_EQ(late_alarms, ros_keys) << "the alarms read from " << journal;
  }
}

}  // namespace
}  // namespace rocking_monitor::test

// main(): test/support/rostest_main.cpp
