#!/usr/bin/env python3
"""Counts the events per channel of LCM log files (the event format of LCM's log files), for the
tests: prints 'CHANNEL COUNT' lines, sorted by channel. --since T counts only the events logged
at or after T (seconds since the epoch)."""
import collections
import struct
import sys

SYNC = 0xEDA1DA01


def channels(path, since_us=0):
    counts = collections.Counter()
    with open(path, "rb") as f:
        while True:
            head = f.read(28)
            if len(head) < 28:
                break
            sync, _num, utime, channel_len, data_len = struct.unpack(">IqqII", head)
            if sync != SYNC:
                raise SystemExit(f"{path}: bad sync word in the log")
            channel = f.read(channel_len).decode()
            if utime >= since_us:
                counts[channel] += 1
            f.seek(data_len, 1)
    return counts


if __name__ == "__main__":
    args = sys.argv[1:]
    since_us = 0
    if args[:1] == ["--since"]:
        since_us = int(float(args[1]) * 1e6)
        args = args[2:]
    total = collections.Counter()
    for log in args:
        total.update(channels(log, since_us))
    for name in sorted(total):
        print(name, total[name])
