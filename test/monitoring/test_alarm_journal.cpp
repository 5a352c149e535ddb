// The alarm journal (issue 19, part 2): records written are read back field for field, events open
// and close by the rules of docs/journal.md, a line cut by a power cut is dropped with a warning that
// names file and line, a corrupt line is reported as file:line and skipped.
#include "rocking_monitor/monitoring/alarm_journal.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "temp_root.hpp"

namespace rocking_monitor::core {
namespace {

const testing::TempRoot& root = testing::TempRoot::registered("rocking_journal_test_");

std::string fresh(const std::string& name) {
  std::filesystem::create_directories(root.path());
  const std::string p = (root.path() / name).string();
  std::filesystem::remove(p);
  return p;
}

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

JournalRecord alarm(const std::string& item, int level, double t) {
  JournalRecord r;
  r.kind = JournalKind::Alarm;
  r.item = item;
  r.level = level;
  r.plane = "y";
  r.sensor = "floor";
  r.time = t;
  r.rotation_ratio = 1.0 + 1.0 / 3.0;
  r.stamp_ns = static_cast<std::int64_t>(t * 1e9) + 1;  // not a multiple of 1 us: exact only as an integer
  return r;
}

constexpr double kRun = 758809855.0;   // 1994-01-17T12:30:55Z (Northridge): the first sample
constexpr double kNow = 1700000000.0;  // the node's clock

TEST(AlarmJournal, RecordsAreReadBackExactlyAndNumberedWithinTheEvent) {
  const std::string p = fresh("a/b/journal.jsonl");  // directories are created
  AlarmJournal j;
  ASSERT_EQ(j.open(p, 3600.0, kNow), "");
  EXPECT_FALSE(j.event().open());
  JournalRecord a = alarm("vase", 4, kRun + 7.125);
  ASSERT_EQ(j.append(a, kRun, kNow), "");
  EXPECT_EQ(a.event, "1994-01-17T12:30:55.000Z/1");
  EXPECT_EQ(a.sequence, 1u);
  EXPECT_EQ(a.since_event_start, 7.125);
  JournalRecord p2;
  p2.kind = JournalKind::ProbabilityAlarm;
  p2.item = "urn";
  p2.level = 3;
  p2.time = kRun + 9.0;
  p2.probability = 0.53125;  // 17 of 32
  p2.lower = 0.36;
  p2.upper = 0.69;
  p2.threshold = 0.5;
  p2.ensemble_size = 32;
  // Another sensor run later in the same event: the event keeps its first sample.
  ASSERT_EQ(j.append(p2, kRun + 5.0, kNow + 1.0), "");
  EXPECT_EQ(p2.event, a.event);
  EXPECT_EQ(p2.sequence, 2u);
  EXPECT_EQ(p2.since_event_start, 9.0);
  JournalRecord stale;
  ASSERT_EQ(j.append_stale("floor", kRun + 20.0, kRun + 23.5, kRun, kNow + 2.0, &stale), "");
  EXPECT_EQ(stale.sequence, 3u);
  EXPECT_TRUE(j.holds(JournalKind::Alarm, "vase", 4));
  EXPECT_FALSE(j.holds(JournalKind::Alarm, "vase", 3));
  EXPECT_FALSE(j.holds(JournalKind::ProbabilityAlarm, "vase", 4));

  const JournalReading r = read_journal(p);
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_TRUE(r.errors.empty());
  ASSERT_EQ(r.records.size(), 3u);
  EXPECT_EQ(r.events, 1u);
  const JournalRecord& back = r.records[0];
  EXPECT_EQ(back.kind, JournalKind::Alarm);
  EXPECT_EQ(back.item, "vase");
  EXPECT_EQ(back.level, 4);
  EXPECT_EQ(back.plane, "y");
  EXPECT_EQ(back.sensor, "floor");
  EXPECT_EQ(back.time, kRun + 7.125);
  EXPECT_EQ(back.rotation_ratio, 1.0 + 1.0 / 3.0);  // doubles round-trip exactly
  EXPECT_EQ(back.stamp_ns, a.stamp_ns);
  EXPECT_EQ(back.event_start, kRun);
  EXPECT_EQ(back.written, kNow);
  EXPECT_EQ(r.records[1].probability, 0.53125);
  EXPECT_EQ(r.records[1].ensemble_size, 32);
  EXPECT_EQ(r.records[2].kind, JournalKind::Stale);
  EXPECT_EQ(r.records[2].end_time, kRun + 23.5);
  // One line per record, the level by name.
  const std::string text = slurp(p);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3);
  EXPECT_NE(text.find("\"level\":\"OVERTURNED\""), std::string::npos) << text;
}

// An item that slid off its plinth (issue 51): its OVERTURNED alarm carries the cause, by name, and
// reads back; an overturn by rocking writes no cause (the lines of older journals) and reads as rocking;
// a cause the reader does not know is a corrupt line naming it.
TEST(AlarmJournal, TheCauseFellOffItsSupportIsWrittenByNameAndReadBack) {
  const std::string p = fresh("cause/journal.jsonl");
  AlarmJournal j;
  ASSERT_EQ(j.open(p, 3600.0, kNow), "");
  JournalRecord off = alarm("bust", 4, kRun + 3.5);
  off.cause = AlarmCause::FellOffSupport;
  JournalRecord rocked = alarm("vase", 4, kRun + 4.0);
  ASSERT_EQ(j.append(off, kRun, kNow), "");
  ASSERT_EQ(j.append(rocked, kRun, kNow), "");
  const std::string text = slurp(p);
  const std::size_t second_line = text.find('\n') + 1;
  EXPECT_NE(text.find("\"cause\":\"fell_off_support\""), std::string::npos) << text;
  EXPECT_EQ(text.find("\"cause\"", second_line), std::string::npos) << text;
  const JournalReading r = read_journal(p);
  ASSERT_EQ(r.records.size(), 2u);
  EXPECT_TRUE(r.errors.empty());
  EXPECT_EQ(r.records[0].cause, AlarmCause::FellOffSupport);
  EXPECT_EQ(r.records[1].cause, AlarmCause::Rocking);

  std::ofstream(p, std::ios::app) << R"({"kind":"alarm","event":"1994-01-17T12:30:55.000Z/1","sequence":3,)"
                                  << R"("item":"urn","level":"OVERTURNED","plane":"3d","cause":"fell_off_roof",)"
                                  << R"("time":758809860.0,"event_start":758809855.0,"since_event_start":5.0,)"
                                  << R"("written":1700000000.0})" << "\n";
  const JournalReading bad = read_journal(p);
  EXPECT_EQ(bad.records.size(), 2u);
  ASSERT_EQ(bad.errors.size(), 1u);
  EXPECT_NE(bad.errors[0].find("unknown cause 'fell_off_roof'"), std::string::npos) << bad.errors[0];
}

// The monitor appends a sample's alarms without sync and calls sync() before it publishes them: the
// lines reach the file then, in order, in one write; closing the journal writes what is left.
TEST(AlarmJournal, LinesAppendedWithoutSyncReachTheFileAtSyncInOrder) {
  const std::string p = fresh("batched.jsonl");
  {
    AlarmJournal j;
    ASSERT_EQ(j.open(p, 3600.0, kNow), "");
    for (int k = 0; k < 3; ++k) {
      JournalRecord a = alarm("item" + std::to_string(k), 4, kRun + k);
      ASSERT_EQ(j.append(a, kRun, kNow, false), "");
    }
    EXPECT_EQ(slurp(p), "");  // not yet: nothing is published before sync()
    EXPECT_TRUE(j.holds(JournalKind::Alarm, "item2", 4));
    ASSERT_EQ(j.sync(), "");
    const JournalReading r = read_journal(p);
    ASSERT_EQ(r.records.size(), 3u);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(r.records[k].item, "item" + std::to_string(k));
      EXPECT_EQ(r.records[k].sequence, static_cast<std::uint64_t>(k + 1));
    }
    EXPECT_EQ(j.sync(), "");  // nothing pending: nothing written twice
    JournalRecord late = alarm("late", 4, kRun + 9.0);
    ASSERT_EQ(j.append(late, kRun, kNow, false), "");
    // An end (written with fsync) follows the lines still waiting, not the other way round.
    ASSERT_EQ(j.append_end("shaking stopped", kRun + 30.0, kNow + 30.0), "");
    JournalRecord last = alarm("last", 4, kRun + 40.0);
    ASSERT_EQ(j.append(last, kRun + 40.0, kNow + 40.0, false), "");
  }  // closed without sync()
  const std::string text = slurp(p);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 6);
  EXPECT_LT(text.find("\"late\""), text.find("\"end\""));
  EXPECT_LT(text.find("\"end\""), text.find("\"last\""));
}

// The monitor hands a sample's lines to the journal's thread (sync_async) and publishes its alarms in
// `after`: `after` must see the lines on disk, run off the caller's thread, and every later write must
// wait for it, so that the file keeps the order of the appends.
TEST(AlarmJournal, SyncAsyncRunsAfterOnlyWithTheLinesOnDiskAndKeepsTheOrder) {
  const std::string p = fresh("async.jsonl");
  std::vector<std::string> seen;  // what `after` read from the file, per call
  std::vector<std::thread::id> threads;
  std::vector<std::string> errors;
  {
    AlarmJournal j;
    ASSERT_EQ(j.open(p, 3600.0, kNow), "");
    for (int sample = 0; sample < 50; ++sample) {
      for (int k = 0; k < 4; ++k) {
        JournalRecord a = alarm("item" + std::to_string(4 * sample + k), 2 + k % 3, kRun + sample + 0.1 * k);
        ASSERT_EQ(j.append(a, kRun, kNow + sample, false), "");
      }
      j.sync_async([&, sample](const std::string& e) {
        errors.push_back(e);
        threads.push_back(std::this_thread::get_id());
        const std::string text = slurp(p);
        seen.push_back(text);
        EXPECT_NE(text.find("\"item" + std::to_string(4 * sample + 3) + "\""), std::string::npos) << sample;
      });
      if (sample == 20) {  // a record written with its own fsync in between
        ASSERT_EQ(j.append_stale("floor", kRun + 20.5, kRun + 20.7, kRun, kNow + 20.5), "");
      }
    }
    j.drain();
    EXPECT_EQ(seen.size(), 50u);
  }
  ASSERT_EQ(errors.size(), 50u);
  for (const std::string& e : errors) EXPECT_EQ(e, "");
  for (const std::thread::id& id : threads) EXPECT_NE(id, std::this_thread::get_id());
  const JournalReading r = read_journal(p);
  ASSERT_EQ(r.records.size(), 201u);
  for (std::size_t i = 0; i < r.records.size(); ++i) EXPECT_EQ(r.records[i].sequence, i + 1) << i;
  EXPECT_EQ(r.records[84].kind, JournalKind::Stale);  // after sample 20's four alarms
  // Without a file, `after` runs at once on the caller's thread.
  AlarmJournal off;
  ASSERT_EQ(off.open("", 3600.0, kNow), "");
  bool ran = false;
  std::thread::id caller;
  off.sync_async([&](const std::string& e) {
    ran = e.empty();
    caller = std::this_thread::get_id();
  });
  EXPECT_TRUE(ran);
  EXPECT_EQ(caller, std::this_thread::get_id());
}

TEST(AlarmJournal, EventStaysOpenWithinTheWindowAndClosesAfterItOrOnReset) {
  const std::string p = fresh("window.jsonl");
  {
    AlarmJournal j;
    ASSERT_EQ(j.open(p, 3600.0, kNow), "");
    JournalRecord a = alarm("vase", 2, kRun + 1.0);
    ASSERT_EQ(j.append(a, kRun, kNow), "");
  }
  const JournalReading r = read_journal(p);
  EXPECT_TRUE(open_event(r, kNow + 3600.0, 3600.0).open());   // at the window's end: still open
  EXPECT_FALSE(open_event(r, kNow + 3600.5, 3600.0).open());  // past it: closed
  EXPECT_FALSE(open_event(r, kRun, 3600.0).open());  // a clock far behind (sim time, an old record): closed
  {
    // A restarted node within the window continues the event and its numbering.
    AlarmJournal j;
    ASSERT_EQ(j.open(p, 3600.0, kNow + 10.0), "");
    ASSERT_TRUE(j.event().open());
    EXPECT_EQ(j.event().records.size(), 1u);
    JournalRecord b = alarm("vase", 3, kRun + 2.0);
    ASSERT_EQ(j.append(b, kRun + 100.0, kNow + 20.0), "");
    EXPECT_EQ(b.event, "1994-01-17T12:30:55.000Z/1");
    EXPECT_EQ(b.sequence, 2u);
    // A record after the window closed opens event 2, numbered from 1 again.
    JournalRecord c = alarm("vase", 2, kRun + 9000.0);
    ASSERT_EQ(j.append(c, kRun + 8990.0, kNow + 20.0 + 3601.0), "");
    EXPECT_EQ(c.event, "1994-01-17T15:00:45.000Z/2");
    EXPECT_EQ(c.sequence, 1u);
    EXPECT_EQ(c.since_event_start, 10.0);
    // A reset closes it; the next record opens event 3.
    ASSERT_EQ(j.append_reset("~reset called", kNow + 4000.0), "");
    EXPECT_FALSE(j.event().open());
    EXPECT_FALSE(j.holds(JournalKind::Alarm, "vase", 2));
  }
  const JournalReading after = read_journal(p);
  EXPECT_EQ(after.events, 2u);
  bool reset = false;
  const OpenEvent last = last_event(after, &reset);
  EXPECT_TRUE(reset);
  EXPECT_EQ(last.id, "1994-01-17T15:00:45.000Z/2");  // the report still finds what the reset closed
  EXPECT_FALSE(open_event(after, kNow + 4001.0, 3600.0).open());
  AlarmJournal j;
  ASSERT_EQ(j.open(p, 3600.0, kNow + 4001.0), "");
  JournalRecord d = alarm("urn", 4, kRun + 9500.0);
  ASSERT_EQ(j.append(d, kRun + 9490.0, kNow + 4002.0), "");
  EXPECT_EQ(d.event.substr(d.event.size() - 2), "/3");
}

// Issue 29: an event ends when the shaking has stopped: its end record is its last, numbered on; a later
// shaking (an aftershock) is a new event in which the same levels alarm again, also after a restart.
TEST(AlarmJournal, AnEndClosesTheEventAndTheNextShakingIsANewOne) {
  const std::string p = fresh("end.jsonl");
  {
    AlarmJournal j;
    ASSERT_EQ(j.open(p, 3600.0, kNow), "");
    EXPECT_EQ(j.append_end("nothing open", kRun, kNow), "");  // nothing to end: nothing written
    JournalRecord a = alarm("vase", 4, kRun + 3.0);
    ASSERT_EQ(j.append(a, kRun, kNow), "");
    ASSERT_TRUE(j.holds(JournalKind::Alarm, "vase", 4));
    ASSERT_EQ(j.append_end("shaking stopped", kRun + 25.0, kNow + 20.0), "");
    EXPECT_FALSE(j.event().open());
    EXPECT_FALSE(j.holds(JournalKind::Alarm, "vase", 4));  // the aftershock may alarm it again
  }
  JournalReading r = read_journal(p);
  ASSERT_EQ(r.records.size(), 2u);
  EXPECT_EQ(r.records[1].kind, JournalKind::End);
  EXPECT_EQ(r.records[1].event, "1994-01-17T12:30:55.000Z/1");
  EXPECT_EQ(r.records[1].sequence, 2u);
  EXPECT_EQ(r.records[1].time, kRun + 25.0);
  EXPECT_EQ(r.records[1].reason, "shaking stopped");
  EXPECT_FALSE(open_event(r, kNow + 30.0, 3600.0).open());  // a restart within the window: nothing open
  bool closed = false;
  EXPECT_EQ(last_event(r, &closed).records.size(), 2u);  // the report still finds the ended event
  EXPECT_TRUE(closed);
  EXPECT_EQ(shown_event(r, kNow + 30.0, 3600.0).records.size(), 2u);  // a late dashboard still shows it
  EXPECT_FALSE(shown_event(r, kNow + 3700.0, 3600.0).open());         // not past the window
  AlarmJournal j;
  ASSERT_EQ(j.open(p, 3600.0, kNow + 60.0), "");
  EXPECT_FALSE(j.event().open());
  JournalRecord b = alarm("vase", 4, kRun + 63.0);
  ASSERT_EQ(j.append(b, kRun + 60.0, kNow + 60.0), "");
  EXPECT_EQ(b.event, "1994-01-17T12:31:55.000Z/2");
  EXPECT_EQ(b.sequence, 1u);
}

TEST(AlarmJournal, LineCutByAPowerCutIsDroppedWithAWarningNamingFileAndLine) {
  const std::string p = fresh("cut.jsonl");
  {
    AlarmJournal j;
    ASSERT_EQ(j.open(p, 3600.0, kNow), "");
    JournalRecord a = alarm("vase", 2, kRun + 1.0), b = alarm("vase", 3, kRun + 2.0);
    ASSERT_EQ(j.append(a, kRun, kNow), "");
    ASSERT_EQ(j.append(b, kRun, kNow), "");
  }
  const std::string whole = slurp(p);
  const std::string third = to_json_line(alarm("vase", 4, kRun + 3.0));
  {
    std::ofstream out(p, std::ios::app | std::ios::binary);
    out << third.substr(0, third.size() / 2);  // the power went off mid-write
  }
  const JournalReading r = read_journal(p);
  ASSERT_EQ(r.records.size(), 2u);
  EXPECT_TRUE(r.errors.empty());
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0].rfind(p + ":3: last line cut in the middle", 0), 0u) << r.warnings[0];
  EXPECT_EQ(r.whole_bytes, whole.size());
  // The writer cuts the file back to its whole lines before it appends.
  AlarmJournal j;
  ASSERT_EQ(j.open(p, 3600.0, kNow + 1.0), "");
  EXPECT_EQ(j.reading().warnings.size(), 1u);
  EXPECT_EQ(slurp(p), whole);
  JournalRecord c = alarm("vase", 4, kRun + 3.0);
  ASSERT_EQ(j.append(c, kRun, kNow + 1.0), "");
  EXPECT_EQ(c.sequence, 3u);
  const JournalReading again = read_journal(p);
  EXPECT_TRUE(again.warnings.empty());
  EXPECT_TRUE(again.errors.empty());
  EXPECT_EQ(again.records.size(), 3u);
}

TEST(AlarmJournal, CorruptLinesAreReportedAsFileAndLineAndSkipped) {
  const std::string p = fresh("corrupt.jsonl");
  const std::string good = to_json_line([] {
    JournalRecord a = alarm("vase", 4, kRun + 3.0);
    a.event = "E/1";
    a.sequence = 1;
    a.event_start = kRun;
    a.since_event_start = 3.0;
    a.written = kNow;
    return a;
  }());
  {
    std::ofstream out(p, std::ios::binary);
    out << good << "\n"
        << "{\"kind\": \"alarm\", \"event\": \"E/1\"\n"                  // 2: cut JSON
        << "\n"                                                           // 3: blank: ignored
        << "{\"kind\":\"fire\",\"written\":1,\"time\":1}\n"               // 4: unknown kind
        << "[1,2]\n"                                                      // 5: not an object
        << good.substr(0, good.find("OVERTURNED")) + "TOPPLED" + good.substr(good.find("OVERTURNED") + 10) << "\n"
        << good << "\r\n";                                                // 7: CRLF is fine
  }
  const JournalReading r = read_journal(p);
  EXPECT_EQ(r.records.size(), 2u);
  ASSERT_EQ(r.errors.size(), 4u);
  EXPECT_EQ(r.errors[0].rfind(p + ":2: not a journal record", 0), 0u) << r.errors[0];
  EXPECT_EQ(r.errors[1].rfind(p + ":4: ", 0), 0u) << r.errors[1];
  EXPECT_NE(r.errors[1].find("unknown kind 'fire'"), std::string::npos) << r.errors[1];
  EXPECT_EQ(r.errors[2].rfind(p + ":5: ", 0), 0u) << r.errors[2];
  EXPECT_NE(r.errors[3].find(":6: "), std::string::npos) << r.errors[3];
  EXPECT_NE(r.errors[3].find("unknown level 'TOPPLED'"), std::string::npos) << r.errors[3];
  EXPECT_TRUE(r.warnings.empty());
}

// A journal keeps every event since it was created; a restart needs only the last one (the only one
// that can be open) and the count (to number the next). The reading keeps that event's records, and
// reports corrupt lines anywhere in the file.
TEST(AlarmJournal, ManyEventsAreCountedAndOnlyTheLastIsKept) {
  const std::string p = fresh("many.jsonl");
  constexpr int kEvents = 40;
  std::vector<JournalRecord> last;  // the last event's records as written
  {
    AlarmJournal j;
    ASSERT_EQ(j.open(p, 3600.0, kNow), "");
    for (int e = 0; e < kEvents; ++e) {
      const double run = kRun + 100.0 * e, now = kNow + 100.0 * e;
      for (int k = 0; k < 25; ++k) {
        JournalRecord a = alarm("item" + std::to_string(k), 2 + k % 3, run + 1.0 + k);
        ASSERT_EQ(j.append(a, run, now), "");
        if (e == kEvents - 1) last.push_back(a);
      }
      if (e == 7) {
        ASSERT_EQ(j.append_reset("operator", now + 50.0), "");  // closes event 8 without an end
        continue;
      }
      if (e < kEvents - 1) ASSERT_EQ(j.append_end("shaking stopped", run + 60.0, now + 60.0), "");
    }
    ASSERT_EQ(j.append_reset("operator", kNow + 100.0 * kEvents), "");  // after the last event
  }
  // A corrupt line in an old event (line 3) is still reported, with its line.
  std::string text = slurp(p);
  const std::size_t second = text.find('\n', text.find('\n') + 1) + 1;
  text.insert(second, "garbage\n");
  std::ofstream(p, std::ios::binary | std::ios::trunc) << text;

  const JournalReading r = read_journal(p);
  EXPECT_EQ(r.events, static_cast<std::uint64_t>(kEvents));
  EXPECT_TRUE(r.warnings.empty());
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].rfind(p + ":3: not a journal record", 0), 0u) << r.errors[0];
  EXPECT_EQ(r.whole_bytes, text.size());
  // The last event's 25 alarms, then the reset after it: nothing of the 39 events before.
  ASSERT_EQ(r.records.size(), last.size() + 1);
  for (std::size_t i = 0; i < last.size(); ++i) {
    EXPECT_EQ(r.records[i].event, last[i].event);
    EXPECT_EQ(r.records[i].item, last[i].item);
    EXPECT_EQ(r.records[i].sequence, last[i].sequence);
    EXPECT_EQ(r.records[i].time, last[i].time);
  }
  EXPECT_EQ(r.records.back().kind, JournalKind::Reset);
  bool closed = false;
  const OpenEvent ev = last_event(r, &closed);
  EXPECT_EQ(ev.id, last[0].event);
  EXPECT_EQ(ev.records.size(), last.size());
  EXPECT_TRUE(closed);  // the reset after it
  EXPECT_EQ(ev.id, "1994-01-17T13:35:55.000Z/40");

  // Without the reset, the last event is open at a restart within the window and continues.
  text.resize(text.rfind('\n', text.size() - 2) + 1);
  std::ofstream(p, std::ios::binary | std::ios::trunc) << text;
  AlarmJournal j;
  ASSERT_EQ(j.open(p, 3600.0, kNow + 100.0 * kEvents), "");
  ASSERT_TRUE(j.event().open());
  EXPECT_EQ(j.event().id, last[0].event);
  EXPECT_EQ(j.event().records.size(), last.size());
  EXPECT_TRUE(j.holds(JournalKind::Alarm, "item24", 2));
  JournalRecord more = alarm("vase", 4, kRun + 100.0 * (kEvents - 1) + 40.0);
  ASSERT_EQ(j.append(more, kRun + 100.0 * (kEvents - 1), kNow + 100.0 * kEvents), "");
  EXPECT_EQ(more.event, last[0].event);
  EXPECT_EQ(more.sequence, last.size() + 1);
  // After its end, the next event is numbered after all the others.
  ASSERT_EQ(j.append_end("shaking stopped", kRun + 100.0 * kEvents, kNow + 100.0 * kEvents + 1.0), "");
  JournalRecord next = alarm("vase", 4, kRun + 100.0 * kEvents + 50.0);
  ASSERT_EQ(j.append(next, kRun + 100.0 * kEvents + 50.0, kNow + 100.0 * kEvents + 2.0), "");
  EXPECT_EQ(next.event.substr(next.event.find('/')), "/41");
}

TEST(AlarmJournal, MissingFileIsAnEmptyJournalAndAnUnwritablePathIsAnError) {
  const JournalReading r = read_journal((root.path() / "none.jsonl").string());
  EXPECT_FALSE(r.exists);
  EXPECT_TRUE(r.records.empty());
  const std::string blocker = fresh("file_not_dir");
  std::ofstream(blocker) << "x";
  AlarmJournal j;
  const std::string e = j.open(blocker + "/journal.jsonl", 3600.0, kNow);
  EXPECT_NE(e.find(blocker), std::string::npos) << e;
  EXPECT_FALSE(j.is_open());
  JournalRecord a = alarm("vase", 4, kRun);
  EXPECT_NE(j.append(a, kRun, kNow), "");
}

}  // namespace
}  // namespace rocking_monitor::core
