#!/usr/bin/python3
"""Benchmark (issue 52 target, not a test): N authenticated (version-2) datagrams at 2 kHz into a
udp_accel_bridge with a key, on loopback; prints what the bridge published and lost. Needs a running
ROS master and the package's devel space sourced:
    python3 bench/udp_auth_throughput.py 20000"""
import hashlib, hmac, os, socket, struct, subprocess, sys, tempfile, time
import roslib.packages
import rospy
from diagnostic_msgs.msg import DiagnosticArray
from sensor_msgs.msg import Imu

N, RATE = int(sys.argv[1]), 2000.0
key = os.urandom(32)
path = os.path.join(tempfile.mkdtemp(prefix='rocking_bench_'), 'key')
with open(os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600), 'wb') as f: f.write(key)
with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
    s.bind(('127.0.0.1', 0)); port = s.getsockname()[1]
exe = [p for p in roslib.packages.find_node('rocking_monitor', 'udp_accel_bridge') if os.access(p, os.X_OK)][0]
bridge = subprocess.Popen([exe, '__name:=bench', '_rate_hz:=2000.0', '_port:=%d' % port, '_key_file:=' + path,
                           '_topic:=/bench/imu', '_history_length:=0'], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
rospy.init_node('bench_sender')
got = [0]; diag = {}
rospy.Subscriber('/bench/imu', Imu, lambda m: got.__setitem__(0, got[0] + 1), queue_size=100000)
def on_diag(m):
    for st in m.status:
        if st.name.startswith('bench:'): diag.update({kv.key: kv.value for kv in st.values})
rospy.Subscriber('/diagnostics', DiagnosticArray, on_diag)
while 'published' not in diag: time.sleep(0.1)  # the bridge is up
# Busy-waits to each datagram's due time: a sleep's granularity would send bursts.
sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
t0 = time.monotonic()
for seq in range(N):
    body = struct.pack('<4sHHQdddd', b'RMAC', 2, 0, seq, seq / RATE, 0.1, 0.0, 0.0)
    sock.sendto(body + hmac.new(key, body, hashlib.sha256).digest(), ('127.0.0.1', port))
    due = t0 + (seq + 1) / RATE
    while time.monotonic() < due: pass
took = time.monotonic() - t0
time.sleep(3)
print('sent %d in %.2f s (%.0f Hz); bridge: published %s, lost %s, bad tag %s, datagrams %s; subscriber got %d'
      % (N, took, N / took, diag.get('published'), diag.get('lost'), diag.get('dropped, bad tag'), diag.get('datagrams'), got[0]))
bridge.terminate(); bridge.wait()
os.remove(path); os.rmdir(os.path.dirname(path))
