#!/usr/bin/env python3
"""Shares of a solver step's profile by stage, from `perf script` stacks.

Reads the output of `perf script -F ip,sym` of a `perf record --call-graph
dwarf` of vio_replay, keeps the samples whose stack holds ROOT (default
vio::WindowProblem::Solve, the solver step of both the window solver and the
Ceres baseline) and charges each to the first stage met walking down from
ROOT, else to "other". Prints the samples and each stage's share.

usage: scripts/solver_profile_stages.py STACKS [ROOT]
"""

import collections
import re
import sys

# Stage -> pattern over symbol names, for tcvio's window solver and for
# Ceres' trust-region minimiser (whose Schur eliminator builds the normal
# equations inside the linear solver).
STAGES = [
    ("set-up / preprocessing",
     r"WindowLinearization::SetUp|TrustRegionPreprocessor|Reorder|"
     r"ComputeStableSchurOrdering|CreateHessianGraph"),
    ("residuals + Jacobians",
     r"EvaluateResidual|EvaluateGradientAndJacobian|"
     r"WindowLinearization::Correct"),
    ("cost of a candidate step",
     r"CandidateCost|ComputeCandidatePointAndEvaluateCost"),
    ("normal equations", r"BuildNormalEquations"),
    ("Schur elimination, Cholesky, dogleg",
     r"Dogleg|SolveDamped|ComputeTrustRegionStep|QuadraticForm"),
]


def samples(path):
    """Each sample's frames, innermost first."""
    out, cur = [], []
    with open(path) as f:
        for line in f:
            if not line.strip():
                if cur:
                    out.append(cur)
                cur = []
                continue
            m = re.match(r"\s+[0-9a-f]+\s+(.*)", line.rstrip("\n"))
            if m:
                cur.append(m.group(1))
    if cur:
        out.append(cur)
    return out


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__.strip().splitlines()[-1])
    root = sys.argv[2] if len(sys.argv) == 3 else "vio::WindowProblem::Solve"
    stages = [(name, re.compile(p)) for name, p in STAGES]
    counts = collections.Counter()
    n = 0
    for s in samples(sys.argv[1]):
        idx = next((i for i, fr in enumerate(s) if root in fr), None)
        if idx is None:
            continue
        n += 1
        stage = "other"
        for frame in reversed(s[:idx]):
            hit = [name for name, p in stages if p.search(frame)]
            if hit:
                stage = hit[0]
                break
        counts[stage] += 1
    print("samples under %s: %d" % (root, n))
    for stage, c in counts.most_common():
        print("  %-38s %5d %5.1f %%" % (stage, c, 100.0 * c / max(n, 1)))


if __name__ == "__main__":
    main()
