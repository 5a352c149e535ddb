#!/usr/bin/python3
"""rostest: the monitor on a catalogue written by rocking_catalogue from-table (test/ros/own_objects.test).

Every item of the spreadsheet is monitored (it has a state on ~states); the scanned urn, whose entry
carries the 3-D description of an irregular base, runs on the 3-D model (~solid_model auto); the
shelving unit and the vase, given in the spreadsheet as the same objects as the hand-written
config/catalogue_example.yaml, overturn under the demo's pulse as they do there (README)."""
import time
import unittest

import rospy
import rostest
from rocking_monitor.msg import RockingState, RockingStateArray

ITEMS = {"medicine_cabinet", "monitor_cart", "shelving_unit", "server_rack", "lobby_vase", "lobby_urn"}


class OwnObjects(unittest.TestCase):
    def test_every_item_monitored_and_the_example_outcomes(self):
        seen, worst, models, last = set(), {}, {}, [time.time()]

        def on(m):
            for s in m.items:
                seen.add(s.id)
                worst[s.id] = max(worst.get(s.id, 0), s.mode)
                models.setdefault(s.id, set()).add(s.model)
            last[0] = time.time()
        rospy.Subscriber(rospy.get_param("~monitor") + "/states", RockingStateArray, on, queue_size=1000)
        deadline = time.time() + 100
        # the replay is over when nothing arrived for 3 s after some item moved
        while not (worst and max(worst.values()) > 0 and time.time() - last[0] > 3.0):
            self.assertLess(time.time(), deadline, "the replay did not end with motion on ~states")
            time.sleep(0.1)
        self.assertEqual(seen, ITEMS)
        self.assertIn("rocking_3d", models["lobby_urn"])
        for item in ("shelving_unit", "lobby_vase"):
            self.assertEqual(worst[item], RockingState.OVERTURNED, item)


if __name__ == "__main__":
    rospy.init_node("own_objects_check")
    rostest.rosrun("rocking_monitor", "own_objects_check", OwnObjects)
