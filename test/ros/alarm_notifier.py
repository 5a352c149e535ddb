#!/usr/bin/python3
"""rostest (test/ros/alarm_notifier.test): the alarm_notifier node end to end (issue 44).

Real servers on loopback, started here: an SMTP server and a webhook receiver (test/notify/servers.py:
each accepted message is one fsync'd log line) and mosquitto. The node subscribes to the monitor that
replays the demo's one-sine pulse and to two test publishers standing for a redundant pair (/pair_a,
/pair_b: the same alarms, numbered differently, as two monitors do). Checked:
- every alarm of the pulse reaches each channel: the webhook's posts hold each (item, level) once, the
  e-mails list each once, the MQTT channel ends with nothing waiting (/diagnostics);
- the node killed with SIGKILL after its first e-mail and started again (the monitor re-sends its open
  event to it) sends nothing twice (every message id once in each server's log) and loses nothing;
- the pair's copies give one message entry per alarm;
- /diagnostics says when a channel cannot deliver, with the server's reason (the webhook receiver is
  started late: the node reports "Couldn't connect to server" first).
A bad configuration: the node exits (status 2) with one line naming the file, line and field.
Measured and printed: time from the monitor's first COMMITTED alarm to the SMTP server's log.
"""
import json
import os
import shutil
import signal
import socket
import subprocess
import tempfile
import threading
import time
import unittest

import roslib.packages
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from rocking_monitor.msg import OverturnAlarm, RockingStateArray

LEVELS = {2: 'BEYOND_TIPPING', 3: 'COMMITTED', 4: 'OVERTURNED'}
BAG_END = 1000000008.0  # bags/synthetic_one_sine_pulse.bag's last stamp, s


def wait_for(what, predicate, timeout=30.0):
    deadline = time.time() + timeout
    while time.time() < deadline:
        if predicate():
            return
        time.sleep(0.02)
    raise AssertionError('timed out waiting for ' + what + ' (%.1f s)' % timeout)


def free_port():
    with socket.socket() as s:
        s.bind(('127.0.0.1', 0))
        return s.getsockname()[1]


def port_open(port):
    with socket.socket() as s:
        return s.connect_ex(('127.0.0.1', port)) == 0


def read_log(path):
    if not os.path.exists(path):
        return []
    with open(path, encoding='utf-8') as f:
        return [json.loads(line) for line in f if line.strip()]


class NotifierNode(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix='alarm_notifier_')
        self.procs = []
        self.servers = rospy.get_param('~servers')
        self.smtp_port, self.http_port, self.mqtt_port = free_port(), free_port(), free_port()
        self.smtp_log, self.http_log = self.tmp + '/smtp.jsonl', self.tmp + '/http.jsonl'
        self.alarms, self.last_state, self.diag = [], 0.0, []
        self.lock = threading.Lock()
        rospy.Subscriber('/rocking_monitor/alarms', OverturnAlarm, self._alarm, queue_size=1000)
        rospy.Subscriber('/rocking_monitor/states', RockingStateArray, self._state, queue_size=10)
        rospy.Subscriber('/diagnostics', DiagnosticArray, self._diag, queue_size=100)

    def tearDown(self):
        for p in self.procs:
            if p.poll() is None:
                p.kill()
                p.wait()
        shutil.rmtree(self.tmp, ignore_errors=True)

    def _alarm(self, m):
        with self.lock:
            self.alarms.append((m, time.time()))

    def _state(self, m):
        self.last_state = m.header.stamp.to_sec()

    def _diag(self, m):
        with self.lock:
            self.diag += [(s.name, s.level, s.message, {v.key: v.value for v in s.values}.get('waiting'))
                          for s in m.status]

    def start(self, argv, ready_line):
        p = subprocess.Popen(argv, stdout=subprocess.PIPE if ready_line else subprocess.DEVNULL)
        self.procs.append(p)
        if ready_line:
            line = p.stdout.readline().decode()  # blocks until the server listens (or dies: EOF)
            self.assertTrue(line.startswith('ready'), 'server did not start: %s' % argv)
        return p

    def server(self, kind, port, log):
        return self.start(['/usr/bin/python3', self.servers, kind, str(port), log], True)

    def notifier(self, config, outbox):
        exe = [p for p in roslib.packages.find_node('rocking_monitor', 'alarm_notifier') if os.access(p, os.X_OK)][0]
        log = open(self.tmp + '/notifier.log', 'a')
        p = subprocess.Popen([exe, '__name:=alarm_notifier', '_config:=' + config, '_outbox:=' + outbox,
                              '_monitors:=/rocking_monitor,/pair_a,/pair_b'], stdout=log, stderr=subprocess.STDOUT)
        self.procs.append(p)
        return p

    def test_pulse_pair_kill_restart(self):
        self.server('smtp', self.smtp_port, self.smtp_log)
        with open(self.tmp + '/mosquitto.conf', 'w') as f:
            f.write('listener %d 127.0.0.1\nallow_anonymous true\nlog_dest none\n' % self.mqtt_port)
        self.start(['/usr/sbin/mosquitto', '-c', self.tmp + '/mosquitto.conf'], False)
        wait_for('mosquitto', lambda: port_open(self.mqtt_port))
        config = self.tmp + '/notify.yaml'
        with open(config, 'w') as f:
            f.write('''site: Test hospital
dashboard_url: http://127.0.0.1:8080/
window: 1.0
retry: {initial: 0.05, factor: 2.0, max: 0.5}
channels:
  mail: {type: smtp, url: "smtp://127.0.0.1:%d", from: monitor@test.example}
  hook: {type: webhook, url: "http://127.0.0.1:%d/hook"}
  bms: {type: mqtt, host: 127.0.0.1, port: %d, topic_prefix: hospital}
recipients:
  - {name: facilities, channel: mail, to: facilities@test.example}
  - {name: ops, channel: hook}
  - {name: building, channel: bms}
''' % (self.smtp_port, self.http_port, self.mqtt_port))
        outbox = self.tmp + '/outbox.jsonl'
        node = self.notifier(config, outbox)
        # The webhook receiver is not up yet: the node says so in /diagnostics, with the reason.
        wait_for('a COMMITTED alarm', lambda: any(m.level >= 3 for m, _ in self.alarms), 40.0)
        wait_for('the e-mail of the first COMMITTED', lambda: len(read_log(self.smtp_log)) >= 1)
        first_commit = min(t for m, t in self.alarms if m.level >= 3)
        mail_at = read_log(self.smtp_log)[0]['received']
        print('[ measured ] monitor\'s first COMMITTED alarm to the SMTP server\'s log: %.3f s' % (mail_at - first_commit))
        wait_for('/diagnostics naming the refused webhook', lambda: any(
            'channel hook' in n and lvl == 2 and "Couldn't connect to server" in msg for n, lvl, msg, _ in list(self.diag)))
        # Killed with SIGKILL after its first e-mail, started again on the same outbox.
        node.send_signal(signal.SIGKILL)
        node.wait()
        self.server('http', self.http_port, self.http_log)
        self.notifier(config, outbox)
        # The pair: the same three alarms from two monitors, each numbering its own journal.
        pubs = {s: rospy.Publisher('/pair_%s/alarms' % s, OverturnAlarm, queue_size=10, latch=False) for s in 'ab'}
        wait_for('the node subscribed to the pair', lambda: all(p.get_num_connections() > 0 for p in pubs.values()))
        for k in range(3):
            for s, (event, seq0, delay_ns) in {'a': ('2026-11-27T10:00:00.000Z/1', 1, 0),
                                               'b': ('2026-11-27T10:00:00.200Z/1', 4, 2000000)}.items():
                m = OverturnAlarm(item_id='pair_item_%d' % k, description='pair test item', level=4,
                                  event_id=event, sequence=seq0 + k, plane='x', event_time=1000000001.0 + k)
                m.header.stamp = rospy.Time(1000000001 + k, delay_ns)
                pubs[s].publish(m)
        wait_for('the end of the pulse at the monitor (last state %.3f)' % self.last_state,
                 lambda: self.last_state >= BAG_END - 0.1, 40.0)
        expected = sorted({(m.item_id, LEVELS[m.level]) for m, _ in self.alarms} |
                          {('pair_item_%d' % k, 'OVERTURNED') for k in range(3)})
        self.assertGreaterEqual(len(expected), 4)

        def posted():
            return sorted((a['item'], a['level']) for h in read_log(self.http_log) for a in h['alarms'])
        wait_for('every alarm posted to the webhook', lambda: len(posted()) >= len(expected), 30.0)
        self.assertEqual(posted(), expected, 'each alarm once at the webhook')

        def mailed():
            out = []
            for m in read_log(self.smtp_log):
                level = None
                for line in m['body'].splitlines():
                    for name in LEVELS.values():
                        if line.startswith(name + ':'):
                            level = name
                    if line.startswith('  - '):
                        out.append((line[4:].split(' ')[0], level))
            return sorted(out)
        wait_for('every alarm e-mailed', lambda: len(mailed()) >= len(expected), 30.0)
        self.assertEqual(mailed(), expected, 'each alarm once in the e-mails')
        for log in (self.smtp_log, self.http_log):
            ids = [m['id'] for m in read_log(log)]
            self.assertEqual(len(ids), len(set(ids)), '%s: a message twice: %s' % (log, ids))
        # MQTT (its retained state per item is checked in notify_tests): the channel delivered everything.
        with self.lock:
            self.diag = []
        wait_for('/diagnostics: the mqtt channel has nothing waiting', lambda: any(
            'channel bms' in n and lvl == 0 and waiting == '0' for n, lvl, _, waiting in list(self.diag)))
        print('[ measured ] %d alarms, %d e-mails, %d webhook posts' % (
            len(expected), len(read_log(self.smtp_log)), len(read_log(self.http_log))))

    def test_bad_config_is_one_clear_error(self):
        config = self.tmp + '/bad.yaml'
        with open(config, 'w') as f:
            f.write('channels:\n  mail: {type: smtp, url: "smtp://127.0.0.1:25", from: a@b.example}\n'
                    'recipients:\n  - {name: x, channel: mial, to: x@b.example}\n')
        exe = [p for p in roslib.packages.find_node('rocking_monitor', 'alarm_notifier') if os.access(p, os.X_OK)][0]
        run = subprocess.run([exe, '__name:=alarm_notifier_bad', '_config:=' + config, '_outbox:=' + self.tmp + '/o.jsonl'],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=30)
        self.assertEqual(run.returncode, 2)
        self.assertIn("bad.yaml:4: recipients[0].channel: unknown channel 'mial' (defined: mail)", run.stdout.decode())
        self.assertFalse(os.path.exists(self.tmp + '/o.jsonl'), 'nothing started')


if __name__ == '__main__':
    rospy.init_node('alarm_notifier_test')
    rostest.rosrun('rocking_monitor', 'alarm_notifier_e2e', NotifierNode)
