#!/usr/bin/env python3
"""A small SeedLink 3 server for the tests (plain sockets, no SeedLink library).

Serves the 512-byte miniSEED records of the given files (written by record_to_mseed, channels
interleaved) as a recorder's server would: per station sequence numbers 1, 2, ... in file order,
each packet "SL" + 6 upper-case hex digits + the record, released at the pace of its data (the
record's end time, divided by --speed) counted from the moment the first client finished its
handshake. That moment is kept in --clock-file, so a server killed and started again with the same
arguments serves the same packets under the same numbers at the same times; a client resuming with
"DATA <seq>" gets everything from <seq> on.

Protocol (client -> server, lines ending in CR and/or LF):
  HELLO                 -> "SeedLink v3.1 (rocking_monitor test server) :: SLPROTO:3.1" CRLF, organisation CRLF
  STATION <sta> <net>   -> OK | ERROR (unknown station)
  SELECT <selector>     -> OK
  DATA [<seq hex>]      -> OK   (from packet <seq> of the station, else from the next new packet)
  END                   -> packets follow
  INFO ID               -> one "SLINFO  " packet (a keep-alive answer)

Faults for the bridge's tests:
  --unknown-at N   packet N of the first station is a copy of the record before it with the data
                   encoding set to 99 (a real packet with its own sequence number, on every run)
  --realtime       release each record at its own end time (data time = wall time), for latency
  --inject-at N    before packet N (this run only): one malformed header ("SL" + non-hex) and the
                   previous packet again under its old sequence number (a wrong sequence number)
  --conflict-at N  packet N of the first station is a copy of the record before it with every sample
                   1000 counts larger (int32 records only): an overlap with other values, on every run
"""
import argparse
import calendar
import os
import select
import signal
import socket
import struct
import sys
import time


def record_info(rec):
    """(network, station, channel, start s, end s) of a big-endian miniSEED 2 record."""
    sta = rec[8:13].decode().strip()
    chan = rec[15:18].decode().strip()
    net = rec[18:20].decode().strip()
    year, day, hour, minute, sec, _, frac = struct.unpack('>HHBBBBH', rec[20:30])
    nsamp, fact, mult = struct.unpack('>Hhh', rec[30:36])
    if fact > 0 and mult > 0:
        rate = fact * mult
    elif fact > 0 > mult:
        rate = -fact / mult
    elif fact < 0 < mult:
        rate = -mult / fact
    else:
        rate = 1.0 / (fact * mult)
    # Blockette 1001 adds microseconds (libmseed writes it): keep the 100 us header resolution plus it.
    usec = 0
    offset = struct.unpack('>H', rec[46:48])[0]
    while offset and offset + 4 <= len(rec):
        btype, nxt = struct.unpack('>HH', rec[offset:offset + 4])
        if btype == 1001:
            usec = struct.unpack('>b', rec[offset + 5:offset + 6])[0]
        offset = nxt
    start = (calendar.timegm((year, 1, 1, 0, 0, 0, 0, 0, 0)) + (day - 1) * 86400 + hour * 3600 + minute * 60 + sec
             + frac * 1e-4 + usec * 1e-6)
    return net, sta, chan, start, start + nsamp / rate


def conflicting_copy(rec):
    """The record with every int32 sample 1000 counts larger: same channel and times, other values."""
    if rec[52] != 3:
        sys.exit('--conflict-at needs int32 records (record_to_mseed --encoding int32), not encoding %d' % rec[52])
    nsamp = struct.unpack('>H', rec[30:32])[0]
    begin = struct.unpack('>H', rec[44:46])[0]
    order = '>' if rec[53] == 1 else '<'  # blockette 1000's word order
    samples = struct.unpack(order + '%di' % nsamp, rec[begin:begin + 4 * nsamp])
    out = bytearray(rec)
    out[begin:begin + 4 * nsamp] = struct.pack(order + '%di' % nsamp, *(v + 1000 for v in samples))
    return bytes(out)


def load(paths, unknown_at, conflict_at=0):
    """Packets in serving order: dicts with station key, seq, record, release offset (s of data)."""
    packets, seqs = [], {}
    first_key = None
    for path in paths:
        data = open(path, 'rb').read()
        if len(data) % 512:
            sys.exit('%s: %d bytes is not a whole number of 512-byte records' % (path, len(data)))
        for i in range(0, len(data), 512):
            rec = data[i:i + 512]
            net, sta, chan, start, end = record_info(rec)
            key = (net, sta)
            first_key = first_key or key
            if key == first_key and unknown_at and seqs.get(key, 0) + 1 == unknown_at:
                bad = bytearray(packets[-1]['record'])
                bad[52] = 99  # blockette 1000's encoding byte (libmseed puts 1000 at offset 48)
                seqs[key] = seqs.get(key, 0) + 1
                packets.append(dict(key=key, seq=seqs[key], record=bytes(bad), end=packets[-1]['end']))
            if key == first_key and conflict_at and seqs.get(key, 0) + 1 == conflict_at:
                seqs[key] = seqs.get(key, 0) + 1
                packets.append(dict(key=key, seq=seqs[key], record=conflicting_copy(packets[-1]['record']),
                                    end=packets[-1]['end']))
            seqs[key] = seqs.get(key, 0) + 1
            packets.append(dict(key=key, seq=seqs[key], record=rec, end=end))
    t0 = min(p['end'] for p in packets)
    for p in packets:
        p['offset'] = p['end'] - t0
    return packets


class Client:
    def __init__(self, conn):
        self.conn = conn
        self.buf = b''

    def line(self):
        while True:
            for sep in (b'\r\n', b'\n', b'\r'):
                at = self.buf.find(sep)
                if at >= 0:
                    line, self.buf = self.buf[:at], self.buf[at + len(sep):]
                    return line.decode(errors='replace').strip()
            chunk = self.conn.recv(4096)
            if not chunk:
                return None
            self.buf += chunk


def serve(conn, args, packets, injected):
    c = Client(conn)
    stations = {p['key'] for p in packets}
    wanted = {}  # key -> first seq (None: from the next new packet)
    current = None
    while True:
        line = c.line()
        if line is None:
            return
        words = line.split()
        if not words:
            continue
        cmd = words[0].upper()
        if cmd == 'HELLO':
            conn.sendall(b'SeedLink v3.1 (rocking_monitor test server) :: SLPROTO:3.1\r\nrocking_monitor test\r\n')
        elif cmd == 'STATION' and len(words) == 3:
            current = (words[2], words[1])
            conn.sendall(b'OK\r\n' if current in stations else b'ERROR\r\n')
        elif cmd == 'SELECT':
            conn.sendall(b'OK\r\n')
        elif cmd == 'DATA':
            wanted[current] = int(words[1], 16) if len(words) > 1 else None
            conn.sendall(b'OK\r\n')
        elif cmd == 'END':
            break
        elif cmd == 'INFO':
            conn.sendall(b'SLINFO  ' + b' ' * 512)
        else:
            conn.sendall(b'ERROR\r\n')
    first_client = not os.path.exists(args.clock_file)
    if first_client:
        with open(args.clock_file + '.tmp', 'w') as f:
            f.write('%.6f\n' % time.time())
        os.rename(args.clock_file + '.tmp', args.clock_file)
    t0 = float(open(args.clock_file).read())
    # The packets' clock starts with the first client: it gets them all.
    now_offset = float('-inf') if first_client else (time.time() - t0) * args.speed
    if args.realtime:  # a live recorder: each record leaves when its last sample has been taken
        now_offset = time.time()
    last_sent = None
    for i, p in enumerate(packets):
        start = wanted.get(p['key'], 'no')
        if start == 'no':
            continue
        if start is None and (p['end'] if args.realtime else p['offset']) < now_offset:
            continue  # DATA without a number: only packets newer than the request
        if start is not None and p['seq'] < start:
            continue
        release = p['end'] if args.realtime else t0 + p['offset'] / args.speed
        while True:
            wait = release - time.time()
            readable, _, _ = select.select([conn], [], [], max(wait, 0.0))
            if readable:
                more = conn.recv(4096)
                if not more:
                    return
                c.buf += more
                while True:
                    for sep in (b'\r\n', b'\n', b'\r'):
                        at = c.buf.find(sep)
                        if at >= 0:
                            break
                    else:
                        break
                    line, c.buf = c.buf[:at], c.buf[at + len(sep):]
                    if line.strip().upper().startswith(b'INFO'):
                        conn.sendall(b'SLINFO  ' + b' ' * 512)
                continue
            if wait <= 0:
                break
        if args.inject_at and p['seq'] == args.inject_at and p['key'] == packets[0]['key'] and not injected[0] and last_sent:
            injected[0] = True
            conn.sendall(b'SL00ZZ!!' + last_sent['record'])  # malformed header
            conn.sendall(b'SL%06X' % last_sent['seq'] + last_sent['record'])  # a number already used
        conn.sendall(b'SL%06X' % p['seq'] + p['record'])
        if p['key'] == packets[0]['key']:
            last_sent = p
    # All served: keep the connection open (a real server would wait for new data).
    while True:
        readable, _, _ = select.select([conn], [], [], 1.0)
        if readable and not conn.recv(4096):
            return


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--port', type=int, required=True)
    ap.add_argument('--speed', type=float, default=1.0, help='data seconds per wall second')
    ap.add_argument('--clock-file', required=True)
    ap.add_argument('--realtime', action='store_true',
                    help='release each record at its end data time (wall clock), as a live recorder sends it')
    ap.add_argument('--unknown-at', type=int, default=0)
    ap.add_argument('--inject-at', type=int, default=0)
    ap.add_argument('--conflict-at', type=int, default=0)
    ap.add_argument('files', nargs='+')
    args = ap.parse_args()
    packets = load(args.files, args.unknown_at, args.conflict_at)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
    srv = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    srv.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    srv.bind(('127.0.0.1', args.port))
    srv.listen(4)
    print('seedlink_test_server: %d packets on port %d' % (len(packets), args.port), flush=True)
    injected = [False]
    while True:
        conn, _ = srv.accept()
        conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        try:
            serve(conn, args, packets, injected)
        except (BrokenPipeError, ConnectionResetError):
            pass
        conn.close()


if __name__ == '__main__':
    main()
