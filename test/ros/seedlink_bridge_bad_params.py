#!/usr/bin/env python3
"""rostest: seedlink_bridge refuses to start on bad parameters, with one FATAL line naming the
parameter (and never guesses a gain). Each case runs the node binary under its own name."""
import subprocess
import sys
import unittest

import rospy

BRIDGE = None
CASES = [
    # (private parameters, expected words in the FATAL line)
    ({'server': 'localhost:18562', 'streams': ['CI_RIN:HN?']}, '~gain is missing'),
    ({'server': 'localhost:18562', 'streams': ['CI_RIN:HN?'], 'gain': -5.0}, 'must be finite and > 0'),
    ({'server': 'localhost:18562', 'streams': ['CI_RIN:HN?'], 'gain': {'IU_ANMO': 1000.0}}, 'station CI_RIN: ~gain is missing'),
    ({'server': 'localhost:18562', 'streams': ['CIRIN:HN?'], 'gain': 1000.0}, "stream 'CIRIN:HN?': no '_'"),
    ({'server': 'localhost', 'streams': ['CI_RIN:HN?'], 'gain': 1000.0}, "server 'localhost': expected host:port"),
    ({'streams': ['CI_RIN:HN?'], 'gain': 1000.0}, '~server'),
    ({'server': 'localhost:18562', 'gain': 1000.0}, '~streams'),
    ({'server': 'localhost:18562', 'streams': ['CI_RIN:HN?'], 'gain': 1000.0, 'history_length': -1.0},
     '~history_length: -1.000000 s must be in [0, 86400]'),
    ({'server': 'localhost:18562', 'streams': ['CI_RIN:HN?'], 'gain': 1000.0, 'history_max_rate': 0.0},
     'sample rate 0.000000 Hz: must be > 0'),
]


class BadParams(unittest.TestCase):
    def test_each_bad_parameter_stops_the_node(self):
        for i, (params, words) in enumerate(CASES):
            name = '/bad_bridge_%d' % i
            for k, v in params.items():
                rospy.set_param(name + '/' + k, v)
            p = subprocess.run([BRIDGE, '__name:=bad_bridge_%d' % i], capture_output=True, text=True, timeout=30)
            out = p.stdout + p.stderr
            self.assertEqual(p.returncode, 1, '%s: %s' % (params, out))
            self.assertIn(words, out, str(params))
            self.assertIn('FATAL', out)


if __name__ == '__main__':
    import rostest
    rospy.init_node('seedlink_bridge_bad_params')
    BRIDGE = rospy.get_param('~bridge')
    rostest.rosrun('rocking_monitor', 'seedlink_bridge_bad_params', BadParams, sys.argv)
