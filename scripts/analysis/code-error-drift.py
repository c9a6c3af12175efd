#!/usr/bin/env python3
"""Pseudorange error against time per satellite: a receiver's RINEX 3 observations
(ESTIMATE) minus SkyForge's observation truth (TRUTH) at matching epochs, the receiver
clock removed by the mean over the satellites whose PRN is above GEO_MAX (BeiDou-2 GEOs
are C01-C05). Prints each satellite's mean error over six equal spans of the run: a drift
shows as a trend along the row (docs/integrity.md, "What the GEO biases are").

    scripts/analysis/code-error-drift.py ESTIMATE TRUTH [GEO_MAX]
"""
import collections
import sys


def read(path):
    """{time of day (s): {sat: pseudorange (m)}} of a RINEX 3 observation file whose first
    observation type is the code."""
    out, t = {}, None
    with open(path) as f:
        for line in f:
            if line.startswith(">"):
                p = line.split()
                t = round(float(p[4]) * 3600 + float(p[5]) * 60 + float(p[6]), 3)
                out[t] = {}
            elif t is not None and line[:1] in "GC" and line[1:3].isdigit():
                try:
                    out[t][line[:3]] = float(line[3:17])
                except ValueError:
                    pass
    return out


def main():
    estimate, truth = read(sys.argv[1]), read(sys.argv[2])
    geo_max = int(sys.argv[3]) if len(sys.argv) > 3 else 5
    series = collections.defaultdict(list)
    for t in sorted(estimate):
        if t not in truth:
            continue
        common = [s for s in estimate[t] if s in truth[t]]
        ref = [estimate[t][s] - truth[t][s] for s in common if int(s[1:]) > geo_max]
        if not ref:
            continue
        clock = sum(ref) / len(ref)
        for s in common:
            series[s].append(estimate[t][s] - truth[t][s] - clock)
    for s in sorted(series):
        v = series[s]
        k = len(v) // 6
        if k == 0:
            continue
        means = [sum(v[i * k:(i + 1) * k]) / k for i in range(6)]
        print(s, len(v), " ".join("%6.2f" % m for m in means))


if __name__ == "__main__":
    main()
