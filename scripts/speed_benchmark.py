#!/usr/bin/env python3
"""Speed benchmark: the working tree against a baseline revision, same run.

Builds the baseline revision (default 0387e99, main when issue 14 was filed)
and the working tree in separate build folders, then replays every simulated
preset and a real image sequence with both builds, alternating them (ABAB,
then BABA in the next round), and prints per figure the median over the
rounds of the ratio new / baseline, beside each side's median. Ratios taken
seconds apart on the same machine hold where absolute times do not: on a
shared machine those move by 2x from run to run.

Figures, all parsed from vio_replay's own summary except the last two:
  solver step CPU median and p95 [ms]  (CPU time of the solving thread)
  the work per step: window frames and residuals (medians) and iterations
  (the baseline's summary has only the iterations)
  marginalisation CPU median [ms]
  real-time factor of the estimator loop [x]  (the summary's "x real time")
  frames per second of the whole image replay (images, frontend, estimator)
  process CPU time (user + system) [s], wall time [s] and peak resident
  memory [MB] (/usr/bin/time -v); on a shared machine the CPU time is the
  whole-replay figure to trust, the wall time moves with the load
  ATE (posyaw) rmse of each side [m], so speed is never bought with accuracy
  unseen.

Both sides stop each solver step on iterations only: the baseline's configs
have a 0.04 s wall-clock budget per step (which makes a loaded machine cut
steps short), so the baseline runs with its own config files with
max_time_s set to 100 s; the working tree runs with its own config files
as they are (max_time_s 0: no budget). The simulated sequences are written
once by the baseline's vio_sim, so both sides replay identical input.

Builds go through `vbuild` when it is on PATH (the shared machine's build
slots), else `cmake --build -j JOBS` (default 1); ccache is used when
installed. Needs python3, git, cmake and /usr/bin/time (Debian: time).

usage: scripts/speed_benchmark.py [--baseline REV] [--rounds N]
           [--cases a,b,...] [--work DIR] [--jobs N] [--skip-build]
"""

import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# name -> (sequence: "sim_<preset>" or a path under ../shared/data,
#          config file, extra substitutions applied to both sides' configs
#          [, substitutions applied to the new side's config only])
# The baseline always assumed the replayed folder's imu0/sensor.yaml noise;
# the new build assumes its config's densities (imu.noise_from: config, six
# times the datasheet's, chosen for a real IMU). On a simulated sequence,
# whose IMU has the datasheet noise, the new side is therefore told to take
# the sequence's noise too, as the README's accuracy table does with
# --imu-noise sequence; otherwise the ATE columns compare two noise models.
SEQUENCE_NOISE = [(r"noise_from: config", "noise_from: sequence")]

CASES = {
    "default": ("sim_default", "config/default.yaml", [], SEQUENCE_NOISE),
    "stereo": ("sim_stereo", "config/stereo.yaml", [], SEQUENCE_NOISE),
    "aggressive": ("sim_aggressive", "config/default.yaml", [], SEQUENCE_NOISE),
    "aggressive_td": ("sim_aggressive", "config/default.yaml",
                      [(r"estimate_time_offset: false", "estimate_time_offset: true")],
                      SEQUENCE_NOISE),
    "outliers": ("sim_outliers", "config/default.yaml", [], SEQUENCE_NOISE),
    "euroc_v1_01_stereo": ("data/euroc_V1_01_first5s",
                           "config/euroc_stereo.yaml", []),
    # The new build started as the baseline starts (it had only the static
    # start): the same window, so the same work per step (docs/speed.md).
    "euroc_v1_01_stereo_static": ("data/euroc_V1_01_first5s",
                                  "config/euroc_stereo.yaml", [],
                                  [(r"method: auto ", "method: static ")]),
}

FIGURES = [
    # key, label, unit, format
    ("solver_median", "solver step CPU median", "ms", "%.2f"),
    ("solver_p95", "solver step CPU p95", "ms", "%.2f"),
    ("window_frames", "window frames per step median", "-", "%.0f"),
    ("residuals", "residuals per step median", "-", "%.0f"),
    ("iterations", "iterations per step", "-", "%.1f"),
    ("marg_median", "marginalisation CPU median", "ms", "%.2f"),
    ("realtime", "estimator real-time factor", "x", "%.1f"),
    ("frames_per_s", "image replay frames/s", "1/s", "%.1f"),
    ("process_cpu", "process CPU time", "s", "%.2f"),
    ("process_wall", "process wall time", "s", "%.2f"),
    ("peak_rss", "peak RSS", "MB", "%.1f"),
    ("ate", "ATE posyaw rmse", "m", "%.4f"),
]


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, **kw)


def say(msg):
    print(msg, flush=True)


def build(source, build_dir, args):
    cmake = ["cmake", "-S", source, "-B", build_dir,
             "-DCMAKE_BUILD_TYPE=Release", "-DVIO_BUILD_TESTS=OFF",
             "-DVIO_SHARED_DIR=" + args.shared]
    if shutil.which("ccache"):
        cmake.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
    run(cmake, stdout=subprocess.DEVNULL)
    targets = ["--target", "vio_replay", "vio_sim"]
    if shutil.which("vbuild"):
        run(["vbuild", build_dir] + targets, stdout=subprocess.DEVNULL)
    else:
        run(["cmake", "--build", build_dir, "-j", str(args.jobs)] + targets,
            stdout=subprocess.DEVNULL)


def baseline_source(args):
    """The baseline revision's files in WORK/base-src (git archive)."""
    src = os.path.join(args.work, "base-src")
    stamp = os.path.join(src, ".revision")
    rev = run(["git", "-C", REPO, "rev-parse", args.baseline],
              capture_output=True, text=True).stdout.strip()
    if os.path.exists(stamp) and open(stamp).read().strip() == rev:
        return src, rev
    shutil.rmtree(src, ignore_errors=True)
    os.makedirs(src)
    archive = subprocess.Popen(["git", "-C", REPO, "archive", rev],
                               stdout=subprocess.PIPE)
    run(["tar", "-x", "-C", src], stdin=archive.stdout)
    archive.wait()
    with open(stamp, "w") as f:
        f.write(rev + "\n")
    return src, rev


def write_config(text, subs, path):
    for pattern, repl in subs:
        text, n = re.subn(pattern, repl, text)
        if n == 0:
            sys.exit("error: %s: no match for %r" % (path, pattern))
    with open(path, "w") as f:
        f.write(text)


def configs(args, base_src):
    """Per case and side, the config file to replay with."""
    out = {}
    folder = os.path.join(args.work, "configs")
    os.makedirs(folder, exist_ok=True)
    for name in args.cases:
        _, config, subs = CASES[name][:3]
        new_subs = CASES[name][3] if len(CASES[name]) > 3 else []
        base_text = open(os.path.join(base_src, config)).read()
        new_text = open(os.path.join(REPO, config)).read()
        base_path = os.path.join(folder, "base_%s.yaml" % name)
        new_path = os.path.join(folder, "new_%s.yaml" % name)
        write_config(base_text,
                     subs + [(r"max_time_s: *[0-9.eE+-]+", "max_time_s: 100")],
                     base_path)
        write_config(new_text, subs + new_subs, new_path)
        out[name] = {"base": base_path, "new": new_path}
    return out


def sequences(args, sim, base_src):
    """Per case, the sequence folder (simulated ones written once, by the
    baseline's vio_sim from the baseline's preset files)."""
    out = {}
    for name in args.cases:
        seq = CASES[name][0]
        if seq.startswith("sim_"):
            folder = os.path.join(args.work, "sequences", seq)
            if not os.path.isdir(os.path.join(folder, "mav0")):
                shutil.rmtree(folder, ignore_errors=True)
                preset = os.path.join(base_src, "config", seq + ".yaml")
                run([sim, "--config", preset, "--out", folder],
                    stdout=subprocess.DEVNULL)
            out[name] = folder
        else:
            out[name] = os.path.join(args.shared, seq)
    return out


def number(pattern, text):
    m = re.search(pattern, text)
    return float(m.group(1)) if m else None


def parse(text):
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): "
                     r"(?:(\d+):)?(\d+):([\d.]+)", text)
    process_wall = None
    if wall:
        h = float(wall.group(1) or 0)
        process_wall = 3600 * h + 60 * float(wall.group(2)) + float(wall.group(3))
    rss_kb = number(r"Maximum resident set size \(kbytes\): (\d+)", text)
    user = number(r"User time \(seconds\): ([\d.]+)", text)
    system = number(r"System time \(seconds\): ([\d.]+)", text)
    process_cpu = user + system if user is not None and system is not None \
        else None
    return {
        "solver_median": number(r"solver time per step +median ([\d.]+) ms", text),
        "solver_p95": number(r"solver time per step +median [\d.]+ ms, p95 ([\d.]+) ms", text),
        "window_frames": number(r"solver work per step +median ([\d.]+) "
                                r"window frames", text),
        "residuals": number(r"solver work per step +median [\d.]+ window "
                            r"frames, ([\d.]+) residuals", text),
        "iterations": number(r"; ([\d.]+) iterations per step", text),
        "marg_median": number(r"marginalisation +median ([\d.]+) ms", text),
        "realtime": number(r"of data: ([\d.]+)x real time", text),
        "frames_per_s": number(r"full replay ([\d.]+) frames/s", text),
        "process_cpu": process_cpu,
        "process_wall": process_wall,
        "peak_rss": rss_kb / 1024.0 if rss_kb is not None else None,
        "ate": number(r"ATE \(posyaw\) +rmse ([\d.]+) m", text),
    }


def replay(binary, sequence, config, out_dir):
    cmd = ["/usr/bin/time", "-v", binary, sequence, "--config", config,
           "--out", out_dir]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("error: %s failed:\n%s%s" % (" ".join(cmd), p.stdout,
                                               p.stderr))
    return parse(p.stdout + p.stderr)


def median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def report(args, results, base_rev):
    say("")
    say("speed benchmark: working tree (new) against %s (base), %d rounds, "
        "alternating" % (base_rev[:7], args.rounds))
    say("both sides stop on iterations only (base: max_time_s 100 in its own "
        "configs; new: its own configs)")
    say("per figure: median of base, median of new, median over rounds of "
        "new/base (< 1: new smaller)")
    for name in args.cases:
        runs = results[name]
        say("")
        say("%s (%s, %s)" % (name, CASES[name][0], CASES[name][1]))
        say("  %-34s %10s %10s %9s" % ("figure", "base", "new", "new/base"))
        for key, label, unit, fmt in FIGURES:
            base = [r["base"][key] for r in runs]
            new = [r["new"][key] for r in runs]
            if median(base) is None and median(new) is None:
                continue
            ratios = [n / b for b, n in zip(base, new)
                      if b is not None and n is not None and b > 0]
            cell = lambda v: (fmt % v) if v is not None else "-"
            say("  %-34s %10s %10s %9s" % (
                "%s [%s]" % (label, unit), cell(median(base)),
                cell(median(new)),
                ("%.3f" % median(ratios)) if ratios else "-"))


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--baseline", default="0387e99",
                        help="revision to compare with (default 0387e99)")
    parser.add_argument("--rounds", type=int, default=3,
                        help="alternating rounds per case (default 3)")
    parser.add_argument("--cases", default=",".join(CASES),
                        help="comma-separated subset of: " + ", ".join(CASES))
    parser.add_argument("--work", default=os.path.join(REPO, "build",
                                                       "speed_bench"),
                        help="folder for builds, sequences and outputs")
    parser.add_argument("--shared", default=os.path.join(
        os.path.dirname(REPO), "shared"), help="the shared/ folder (data/)")
    parser.add_argument("--jobs", type=int, default=1,
                        help="build jobs without vbuild (default 1)")
    parser.add_argument("--skip-build", action="store_true",
                        help="use the build folders as they are")
    parser.add_argument("--new-build", default=None,
                        help="an existing build folder of the working tree "
                             "to use instead of building WORK/new-build")
    args = parser.parse_args()
    args.cases = [c for c in args.cases.split(",") if c]
    for c in args.cases:
        if c not in CASES:
            sys.exit("error: unknown case %r (known: %s)" % (c, ", ".join(CASES)))
    if args.rounds < 1:
        sys.exit("error: --rounds must be >= 1")
    if not os.path.exists("/usr/bin/time"):
        sys.exit("error: /usr/bin/time is missing (Debian package: time)")
    args.work = os.path.abspath(args.work)
    os.makedirs(args.work, exist_ok=True)

    base_src, base_rev = baseline_source(args)
    builds = {"base": os.path.join(args.work, "base-build"),
              "new": os.path.abspath(args.new_build) if args.new_build
              else os.path.join(args.work, "new-build")}
    if not args.skip_build:
        say("building %s (base) in %s" % (base_rev[:7], builds["base"]))
        build(base_src, builds["base"], args)
        if not args.new_build:
            say("building the working tree (new) in %s" % builds["new"])
            build(REPO, builds["new"], args)
    binary = {side: os.path.join(d, "tools", "vio_replay")
              for side, d in builds.items()}
    seqs = sequences(args, os.path.join(builds["base"], "tools", "vio_sim"),
                     base_src)
    cfgs = configs(args, base_src)

    results = {name: [] for name in args.cases}
    for r in range(args.rounds):
        order = ["base", "new"] if r % 2 == 0 else ["new", "base"]
        for name in args.cases:
            row = {}
            for side in order:
                out = os.path.join(args.work, "out", "%s_%s" % (side, name))
                start = time.time()
                row[side] = replay(binary[side], seqs[name], cfgs[name][side],
                                   out)
                say("round %d/%d %-20s %-4s %6.1f s  solver median %s ms, "
                    "ATE %s m" % (r + 1, args.rounds, name, side,
                                  time.time() - start,
                                  row[side]["solver_median"], row[side]["ate"]))
            results[name].append(row)
    report(args, results, base_rev)


if __name__ == "__main__":
    main()
