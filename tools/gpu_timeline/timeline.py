#!/usr/bin/env python3
"""Prints one stretch of a GPU timeline written by tracer.cpp (see run.sh beside it).

    timeline.py TRACE.csv FIRST [COUNT]

Frames are found by the frame's first kernel (the colour conversion, ConvertFrameViews);
FIRST is the index of the frame to start at (0-based; negative counts from the end) and
COUNT how many frames to print. Each line: microseconds since the frame's start, duration
in microseconds, the CUDA stream (-1: an API call on the host), and what ran (kernels by
the name of their function or lambda's enclosing function, copies with their kind and
bytes: copy1 host to device, copy2 device to host, copy8 device to device). Host calls are
shown where they take longer than 15 us or synchronise.
"""
import re
import sys

NAMES = ('RunKernel', 'SelectKernel', 'RankSortKernel', 'PlaceNewKernel', 'ColumnPassKernel', 'RowPassKernel',
         'BilateralKernel', 'IntegrateBricksKernel', 'SplitKeys', 'RaycastGuide', 'RaycastInto',
         'TrackingLuminanceOf', 'ClippedLuminanceOf', 'ConvertFrameViews', 'BuildLiveLevel',
         'BuildReferenceLevel', 'Normalize', 'Integrate', 'FillDefault', 'Extract', 'cub')


def short(kind, name, size):
    if kind != 'K':
        return f'{name}({size})'
    for n in NAMES:
        if n in name:
            return n
    return name[:60]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    events = []
    with open(sys.argv[1]) as f:
        for line in f:
            p = line.rstrip('\n').split(',')
            if len(p) < 7:
                continue
            if p[0] in ('K', 'M', 'S'):
                events.append((int(p[2]), int(p[3]), int(p[4]), short(p[0], p[1], p[6])))
            elif p[0] == 'A':
                events.append((int(p[2]), int(p[3]), -1, 'host ' + p[1]))
    events.sort()
    starts = [e[0] for e in events if e[3] == 'ConvertFrameViews']
    if not starts:
        sys.exit(f'{sys.argv[1]}: no frame start (ConvertFrameViews) in the trace')
    first = int(sys.argv[2])
    count = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    if first < 0:
        first += len(starts)
    if not 0 <= first < len(starts):
        sys.exit(f'{sys.argv[1]}: {len(starts)} frames; frame {sys.argv[2]} is not among them')
    t0 = starts[first]
    t1 = starts[first + count] if first + count < len(starts) else float('inf')
    print(f'# frame {first} of {len(starts)}: us from its start, us long, stream, what')
    for s, e, stream, what in events:
        if not t0 <= s < t1:
            continue
        if stream == -1 and not ((e - s) > 15e3 or re.search('Synchronize|Wait', what)):
            continue
        print(f'{(s - t0) / 1e3:8.1f} {(e - s) / 1e3:7.1f} {stream:3d} {what}')


if __name__ == '__main__':
    main()
