#!/usr/bin/env python3
"""Tilt error of the restart state at each reset of a replay.

After a failed step the estimator restarts its window from the prediction of
that step (the last accepted state carried to the frame by the IMU) and puts
its tilt prior there (docs/recorded_flights.md, "Review findings"). This
compares that centre with the alternative, the last accepted output (the
frame before), both against the ground truth at the reset's frame, by the
angle between the estimated and true gravity directions in the body (tilt
does not depend on the yaw gauge, so no alignment is needed).

usage: scripts/tilt_at_resets.py LOG TRAJECTORY GROUND_TRUTH
  LOG           vio_replay's printed summary (its "at T ns: cause" reset lines)
  TRAJECTORY    vio_replay's trajectory.tum (the restart state is the row at
                the reset's stamp)
  GROUND_TRUTH  the folder's mav0/state_groundtruth_estimate0/data.csv
"""
import bisect
import math
import re
import statistics
import sys


def gravity_in_body(qw, qx, qy, qz):
    """R^T e_z for the world-from-body rotation q: the third row of R."""
    n = math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
    w, x, y, z = qw / n, qx / n, qy / n, qz / n
    return (2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y))


def tilt_deg(a, b):
    d = sum(i * j for i, j in zip(a, b))
    return math.degrees(math.acos(max(-1.0, min(1.0, d))))


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    log, trajectory, ground_truth = sys.argv[1:4]
    with open(log) as f:
        resets = [int(m.group(1))
                  for m in re.finditer(r"^ +at (\d+) ns: ", f.read(), re.M)]
    rows = []  # (stamp on a 1 ms grid [ns], gravity in body)
    with open(trajectory) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            v = line.split()
            t = int(round(float(v[0]) * 1e3)) * 1000000
            rows.append((t, gravity_in_body(float(v[7]), float(v[4]),
                                            float(v[5]), float(v[6]))))
    truth = []
    with open(ground_truth) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            v = line.split(",")
            truth.append((int(v[0]), gravity_in_body(*map(float, v[4:8]))))
    row_t = [r[0] for r in rows]
    truth_t = [g[0] for g in truth]
    restart, last, change = [], [], []
    for t in resets:
        k = bisect.bisect_left(row_t, t - 1000000)
        if k == 0 or k >= len(rows) or abs(row_t[k] - t) > 2000000:
            continue
        g = truth[min(bisect.bisect_left(truth_t, row_t[k]), len(truth) - 1)][1]
        restart.append(tilt_deg(rows[k][1], g))
        last.append(tilt_deg(rows[k - 1][1], g))
        change.append(tilt_deg(rows[k][1], rows[k - 1][1]))
    print(f"resets {len(resets)}, {len(restart)} with a pose at their stamp")
    for name, v in (("restart state (the prediction)", restart),
                    ("last accepted output", last),
                    ("tilt between the two", change)):
        if v:
            print(f"  {name:32s} mean {statistics.mean(v):.3f} deg, "
                  f"median {statistics.median(v):.3f}, max {max(v):.3f}")


if __name__ == "__main__":
    main()
