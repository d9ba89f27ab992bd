#!/usr/bin/env python3
"""Counts the events per channel of LCM log files (the event format of LCM's log files), for the
tests: prints 'CHANNEL COUNT' lines, sorted by channel."""
import collections
import struct
import sys

SYNC = 0xEDA1DA01


def channels(path):
    counts = collections.Counter()
    with open(path, "rb") as f:
        while True:
            head = f.read(28)
            if len(head) < 28:
                break
            sync, _num, _utime, channel_len, data_len = struct.unpack(">IqqII", head)
            if sync != SYNC:
                raise SystemExit(f"{path}: bad sync word in the log")
            counts[f.read(channel_len).decode()] += 1
            f.seek(data_len, 1)
    return counts


if __name__ == "__main__":
    total = collections.Counter()
    for log in sys.argv[1:]:
        total.update(channels(log))
    for name in sorted(total):
        print(name, total[name])
