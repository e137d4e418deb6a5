#!/usr/bin/env bash
# Re-initialisation after a reset, off against on (issue 10, item 6;
# docs/initialisation.md, "Re-initialisation after a reset"): provokes one
# reset while moving in a stereo sequence, at several times, and replays each
# corrupted copy with init.reinitialize_after_reset false and true. The reset
# is one accelerometer x value of 1e6 m/s^2 with the range check off
# (imu.accelerometer_range 1e9), so that the prediction explodes and the
# pre-solve check resets the window. Prints one markdown row per fault: the
# truth's speed there, resets, ATE off and on, their ratio, when the
# re-initialisation came; then per case the clean runs (no fault, the
# config's own range) off and on, and whether their states.csv are
# byte-identical.
#
#   scripts/reinit_table.sh [--build DIR] [--work DIR] [--data DIR]
#                           [--config FILE] [--only REGEX]
#
#   --build DIR    the build folder holding tools/vio_sim and vio_replay
#                  (default build)
#   --work DIR     sequences, replays and logs (default
#                  DIR_OF_BUILD/reinit_table; sequences are reused)
#   --data DIR     the recorded flights (default ../shared/data)
#   --config FILE  the replay configuration (default config/stereo.yaml);
#                  its reinitialize_after_reset line is set both ways
#   --only REGEX   only the cases whose name matches (grep -E)
#
# Cases: sim_stereo with seeds 1, 2, 3; sim_aggressive and sim_handheld with
# stereo: true; MH_05 and V1_01 with the recorded IMU (vio_sim --flight
# --imu recorded, as docs/recorded_flights.md). Run from the repository root.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build"
work=""
data="$root/../shared/data"
config="$root/config/stereo.yaml"
only="."
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --work) work="$2"; shift 2 ;;
    --data) data="$2"; shift 2 ;;
    --config) config="$2"; shift 2 ;;
    --only) only="$2"; shift 2 ;;
    -h|--help) sed -n '2,28p' "$0"; exit 0 ;;
    *) echo "error: unknown argument $1 (see --help)" >&2; exit 1 ;;
  esac
done
[ -n "$work" ] || work="$build/reinit_table"
sim="$build/tools/vio_sim"
replay="$build/tools/vio_replay"
for tool in "$sim" "$replay"; do
  if [ ! -x "$tool" ]; then
    echo "error: $tool is missing (vbuild $build --target vio_sim vio_replay)" >&2
    exit 1
  fi
done
mkdir -p "$work/runs"
grep -q 'reinitialize_after_reset: ' "$config" || {
  echo "error: $config has no reinitialize_after_reset line" >&2; exit 1; }
setreinit() { sed -E "s/reinitialize_after_reset: (false|true)/reinitialize_after_reset: $1/" "$2"; }
setreinit false "$config" > "$work/clean_off.yaml"
setreinit true "$config" > "$work/clean_on.yaml"
for c in off on; do
  sed -E 's/^  accelerometer_range: .*/  accelerometer_range: 1.0e9/' \
    "$work/clean_$c.yaml" > "$work/fault_$c.yaml"
done

# case NAME TIMES: the cases and their fault times [s after the first IMU
# sample], spread over the motion.
sim_times="6.03 12.03 18.03 24.03 30.03"
cases=(
  "sim_stereo_seed1:$sim_times" "sim_stereo_seed2:$sim_times"
  "sim_stereo_seed3:$sim_times" "sim_aggressive_stereo:$sim_times"
  "sim_handheld_stereo:$sim_times"
  "MH_05_recorded_stereo:28.03 42.03 57.03 72.03 97.03"
  "V1_01_recorded_stereo:20.03 45.03 70.03 97.03 117.03")

# make_sequence NAME: vio_sim into $work/NAME unless it is there.
make_sequence() {
  local name="$1" dir="$work/$1" preset
  [ -d "$dir/mav0" ] && return 0
  rm -rf "$dir"
  case "$name" in
    sim_stereo_seed*)
      preset="$work/$name.yaml"
      sed -E "s/^seed: .*/seed: ${name#sim_stereo_seed}/" \
        "$root/config/sim_stereo.yaml" > "$preset"
      "$sim" --config "$preset" --out "$dir" ;;
    sim_*_stereo)
      preset="$work/$name.yaml"
      local base="${name%_stereo}"
      sed -E 's/^  stereo: false/  stereo: true/' \
        "$root/config/$base.yaml" > "$preset"
      "$sim" --config "$preset" --out "$dir" ;;
    MH_05_recorded_stereo)
      "$sim" --config "$root/config/sim_stereo.yaml" \
        --flight "$data/euroc_MH_05_imu_gt" --imu recorded --out "$dir" ;;
    V1_01_recorded_stereo)
      "$sim" --config "$root/config/sim_stereo.yaml" \
        --flight "$data/euroc_V1_01_first5s" --imu recorded --out "$dir" ;;
  esac > "$work/runs/$name.sim.log" 2>&1
}

# replay_run FOLDER CONFIG LOG OUT NOISE: vio_replay; never stops the script.
replay_run() {
  "$replay" "$1" --config "$2" --imu-noise "$5" --out "$4" > "$3" 2>&1 || true
}
ate() { { grep -m1 "ATE (posyaw)" "$1" || echo n/a; } |
  sed -E 's/.*rmse ([0-9.]+) m.*/\1/'; }
resets() { { grep -m1 "^  resets" "$1" || echo n/a; } |
  sed -E 's/^  resets *([0-9]+).*/\1/'; }
# reinit_at LOG T0: seconds after T0 [ns] of each re-initialisation, or "-".
reinit_at() {
  local s
  s=$({ grep "re-initialisation after a reset" "$1" || true; } |
    sed -E 's/.* at ([0-9]+) ns.*/\1/' |
    awk -v t0="$2" '{printf "%s%.2f", (NR>1?", ":""), ($1-t0)*1e-9}')
  echo "${s:--}"
}
first_reset() { { grep -m1 -E "^    at [0-9]+ ns" "$1" || true; } | sed -E 's/^    at ([0-9]+) ns.*/\1/'; }

printf '| case | fault at [s] | speed [m/s] | resets off / on | ATE off [m] | ATE on [m] | on / off | re-initialised [s after the reset] |\n'
printf '| --- | --- | --- | --- | --- | --- | --- | --- |\n'
clean_rows=()
for entry in "${cases[@]}"; do
  name="${entry%%:*}"
  times="${entry#*:}"
  echo "$name" | grep -Eq "$only" || continue
  make_sequence "$name"
  dir="$work/$name"
  noise=sequence
  case "$name" in *_recorded_*) noise=config ;; esac
  imu="$dir/mav0/imu0/data.csv"
  gt="$dir/mav0/state_groundtruth_estimate0/data.csv"
  t0=$(awk -F, 'NR==2{print $1; exit}' "$imu")
  for c in off on; do
    replay_run "$dir" "$work/clean_$c.yaml" "$work/runs/$name.clean_$c.log" \
      "$work/runs/$name.clean_$c" "$noise"
  done
  same=differ
  cmp -s "$work/runs/$name.clean_off/states.csv" \
    "$work/runs/$name.clean_on/states.csv" && same=identical
  clean_rows+=("| $name | $(ate "$work/runs/$name.clean_off.log") | $(ate "$work/runs/$name.clean_on.log") | $(resets "$work/runs/$name.clean_off.log") / $(resets "$work/runs/$name.clean_on.log") | $same |")
  for t in $times; do
    # The IMU line of the first sample at or after t (line 1 is the header).
    line=$(awk -F, -v t0="$t0" -v t="$t" \
      'NR>1 && ($1-t0)*1e-9 >= t {print NR; exit}' "$imu")
    fdir="$work/$name.fault_$t"
    if [ ! -d "$fdir/mav0" ]; then
      rm -rf "$fdir"
      cp -al "$dir" "$fdir"
      rm "$fdir/mav0/imu0/data.csv"
      awk -F, -v OFS=, -v n="$line" 'NR==n{$5="1000000"}1' "$imu" \
        > "$fdir/mav0/imu0/data.csv"
    fi
    t_fault=$(awk -F, -v n="$line" 'NR==n{print $1; exit}' "$imu")
    speed=$(awk -F, -v t="$t_fault" \
      'NR>1 && $1 >= t {printf "%.2f", sqrt($9^2+$10^2+$11^2); exit}' "$gt")
    for c in off on; do
      replay_run "$fdir" "$work/fault_$c.yaml" "$work/runs/$name.$t.$c.log" \
        "$work/runs/$name.$t.$c" "$noise"
    done
    off_log="$work/runs/$name.$t.off.log"
    on_log="$work/runs/$name.$t.on.log"
    a_off=$(ate "$off_log")
    a_on=$(ate "$on_log")
    ratio=$(awk -v a="$a_off" -v b="$a_on" 'BEGIN{if (a+0 > 0 && b+0 > 0) printf "%.3f", b/a; else print "n/a"}')
    r_on=$(first_reset "$on_log")
    printf '| %s | %s | %s | %s / %s | %s | %s | %s | %s |\n' "$name" "$t" \
      "${speed:-n/a}" "$(resets "$off_log")" "$(resets "$on_log")" \
      "$a_off" "$a_on" "$ratio" "$(reinit_at "$on_log" "${r_on:-0}")"
  done
done
printf '\nClean runs (no fault, the configuration'"'"'s own range):\n\n'
printf '| case | ATE off [m] | ATE on [m] | resets off / on | states.csv off / on |\n'
printf '| --- | --- | --- | --- | --- |\n'
for row in "${clean_rows[@]}"; do printf '%s\n' "$row"; done
