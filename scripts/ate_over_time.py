#!/usr/bin/env python3
"""The position error of an estimate over time, to tell a bad start from drift.

usage: scripts/ate_over_time.py EST.tum GT.csv [--split S] [--bin S]

EST is vio_replay's trajectory.tum, GT an EuRoC ground truth
(mav0/state_groundtruth_estimate0/data.csv). Each estimate pose is paired
with the nearest ground-truth stamp within 10 ms; the whole estimate is
aligned once by position and yaw (4 DoF, as vio_replay's "ATE (posyaw)"),
then the rmse is printed for the whole run, for the first S seconds and the
rest (--split, default 20), and per bin of --bin seconds (default 10).
"""
import argparse
import bisect
import math


def read_tum(path):
    poses = []
    for line in open(path):
        if line.startswith('#') or not line.strip():
            continue
        v = line.split()
        poses.append((float(v[0]), (float(v[1]), float(v[2]), float(v[3]))))
    return poses


def read_euroc(path):
    stamps, positions = [], []
    for line in open(path):
        if line.startswith('#') or not line.strip():
            continue
        v = line.split(',')
        stamps.append(int(v[0]) * 1e-9)
        positions.append((float(v[1]), float(v[2]), float(v[3])))
    return stamps, positions


def rms(errors):
    return math.sqrt(sum(e * e for e in errors) / len(errors)) if errors else float('nan')


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('estimate')
    parser.add_argument('ground_truth')
    parser.add_argument('--split', type=float, default=20.0)
    parser.add_argument('--bin', type=float, default=10.0)
    args = parser.parse_args()
    gt_t, gt_p = read_euroc(args.ground_truth)
    pairs = []
    for t, p in read_tum(args.estimate):
        i = bisect.bisect_left(gt_t, t)
        near = min((j for j in (i - 1, i) if 0 <= j < len(gt_t)),
                   key=lambda j: abs(gt_t[j] - t))
        if abs(gt_t[near] - t) < 0.01:
            pairs.append((t, p, gt_p[near]))
    if len(pairs) < 2:
        raise SystemExit('error: fewer than 2 poses paired with the ground truth')
    n = len(pairs)
    me = [sum(p[1][k] for p in pairs) / n for k in range(3)]
    mg = [sum(p[2][k] for p in pairs) / n for k in range(3)]
    # Yaw of the least-squares rotation about z between the centred tracks.
    c_sum = s_sum = 0.0
    for _, e, g in pairs:
        ex, ey, gx, gy = e[0] - me[0], e[1] - me[1], g[0] - mg[0], g[1] - mg[1]
        c_sum += ex * gx + ey * gy
        s_sum += ex * gy - ey * gx
    yaw = math.atan2(s_sum, c_sum)
    c, s = math.cos(yaw), math.sin(yaw)
    t0 = pairs[0][0]
    errors = []
    for t, e, g in pairs:
        ex, ey, ez = e[0] - me[0], e[1] - me[1], e[2] - me[2]
        a = (c * ex - s * ey + mg[0], s * ex + c * ey + mg[1], ez + mg[2])
        errors.append((t - t0, math.dist(a, g)))
    print('ATE (posyaw) rmse %.4f m over %d poses' % (rms([e for _, e in errors]), n))
    print('first %.0f s rmse %.4f m, after %.4f m' % (
        args.split, rms([e for t, e in errors if t < args.split]),
        rms([e for t, e in errors if t >= args.split])))
    last = int(errors[-1][0] // args.bin)
    for b in range(last + 1):
        chunk = [e for t, e in errors if b * args.bin <= t < (b + 1) * args.bin]
        if chunk:
            print('%6.1f to %6.1f s  rmse %.4f m' % (b * args.bin, (b + 1) * args.bin, rms(chunk)))


if __name__ == '__main__':
    main()
