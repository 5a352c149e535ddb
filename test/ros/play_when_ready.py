#!/usr/bin/python3
"""rosbag play once the rostest's nodes are listening (issue 42): a fixed `rosbag play -d N` assumed
every node subscribed within N seconds, which a loaded machine does not keep (a late monitor misses
the start of the bag, a late checker the first alarms). This waits, with no time limit of its own
(the test's time-limit catches a hang), until each TOPIC:N given has at least N subscribers
registered with the master, then runs `rosbag play --wait-for-subscribers` (it publishes once each
of the bag's topics has a connected subscriber) with the remaining arguments.

usage (a launch file's node):
  play_when_ready.py --subscribed /ground/imu:1 --subscribed /rocking_monitor/alarms:1 -- --clock BAG
"""
import os
import sys
import time

import rosgraph


def main(argv):
    argv = [a for a in argv if not a.startswith('__')]  # roslaunch's __name:=, __log:=
    if '--' not in argv:
        sys.exit('usage: play_when_ready.py --subscribed TOPIC:N [...] -- <rosbag play arguments>')
    split = argv.index('--')
    wanted, i = {}, 0
    while i < split:
        if argv[i] != '--subscribed' or i + 1 >= split or ':' not in argv[i + 1]:
            sys.exit('play_when_ready.py: expected --subscribed TOPIC:N, got %r' % argv[i])
        topic, n = argv[i + 1].rsplit(':', 1)
        wanted[topic] = int(n)
        i += 2
    master = rosgraph.Master('/play_when_ready')
    while True:
        try:
            subscribers = dict(master.getSystemState()[1])
        except Exception:  # the master not up yet
            subscribers = {}
        missing = [t for t, n in wanted.items() if len(subscribers.get(t, [])) < n]
        if not missing:
            break
        time.sleep(0.1)
    play = ['rosbag', 'play', '--wait-for-subscribers'] + argv[split + 1:]
    os.execvp(play[0], play)


if __name__ == '__main__':
    main(sys.argv[1:])
