#!/usr/bin/env bash
# The accuracy benchmark (docs/recorded_flights.md): replays every simulated preset
# (config/sim_*.yaml) and every recorded flight (vio_sim --flight, with the
# synthetic and with the recorded IMU, mono and stereo) through vio_replay
# with the shipped configurations (config/default.yaml, config/stereo.yaml)
# and prints one table: ATE, RPE, resets, solver time, real-time factor.
# Runs on a synthetic IMU replay with --imu-noise sequence (the simulator's
# own sensor.yaml holds the noise it added); runs on a recorded IMU with the
# configuration's imu: noise. It builds nothing: build vio_sim and vio_replay
# first.
#
# usage: scripts/accuracy_benchmark.sh [--build DIR] [--work DIR] [--data DIR]
#            [--only REGEX] [--mono-config FILE] [--stereo-config FILE]
#            [--curve imu|ground-truth|both] [--seeds LIST] [--seed N]
#   --build DIR   the build folder holding tools/ (default build)
#   --work DIR    simulated folders and replay logs (default
#                 DIR_OF_BUILD/accuracy_benchmark); folders are made when
#                 missing and reused otherwise
#   --data DIR    the recorded sequences (default ../shared/data)
#   --only REGEX  only the rows whose name matches (grep -E)
#   --mono-config, --stereo-config  replay configurations (default
#                 config/default.yaml, config/stereo.yaml)
#   --curve       the recorded-IMU flights' curve (vio_sim --curve): imu
#                 (default; fitted to the ground truth and the recorded IMU
#                 together; rows *_recorded_imucurve_*), ground-truth (rows
#                 *_recorded_*), or both
#   --seeds LIST  vio_sim's seeds for the recorded flights, comma-separated
#                 (default 1,2,3); a seed other than 1 adds _seedN to its
#                 rows and folders; with more than one seed each flight row
#                 is followed by a *_mean row (ATE, RPE: the mean over the
#                 seeds; resets: their sum)
#   --seed N      the same as --seeds N
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build"
work=""
data="$root/../shared/data"
only="."
mono_config="$root/config/default.yaml"
stereo_config="$root/config/stereo.yaml"
curve="imu"
seeds="1,2,3"
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --work) work="$2"; shift 2 ;;
    --data) data="$2"; shift 2 ;;
    --only) only="$2"; shift 2 ;;
    --mono-config) mono_config="$2"; shift 2 ;;
    --stereo-config) stereo_config="$2"; shift 2 ;;
    --curve) curve="$2"; shift 2 ;;
    --seeds|--seed) seeds="$2"; shift 2 ;;
    -h|--help) sed -n '2,32p' "$0"; exit 0 ;;
    *) echo "error: unknown argument $1 (see --help)" >&2; exit 1 ;;
  esac
done
case "$curve" in
  ground-truth|imu|both) ;;
  *) echo "error: --curve expects ground-truth, imu or both (got $curve)" >&2
     exit 1 ;;
esac
if ! [[ "$seeds" =~ ^[0-9]+(,[0-9]+)*$ ]]; then
  echo "error: --seeds expects comma-separated whole numbers (got $seeds)" >&2
  exit 1
fi
IFS=, read -r -a seed_list <<< "$seeds"
[ -n "$work" ] || work="$build/accuracy_benchmark"
sim="$build/tools/vio_sim"
replay="$build/tools/vio_replay"
for tool in "$sim" "$replay"; do
  if [ ! -x "$tool" ]; then
    echo "error: $tool is missing: build it first (vbuild $build --target" \
         "vio_sim vio_replay)" >&2
    exit 1
  fi
done
mkdir -p "$work/runs"

# Recorded flights: name and folder. (MH_04, quoted in issue 11, is not in
# ../shared/data; MH_01's excerpt is 6 s of hand-held motion without a
# still start, which the static initialiser cannot start from.)
flights=("MH_05:$data/euroc_MH_05_imu_gt" "V1_01:$data/euroc_V1_01_first5s")

# make_folder NAME COMMAND...: runs vio_sim into $work/NAME unless it exists.
make_folder() {
  local name="$1"; shift
  if [ ! -d "$work/$name/mav0" ]; then
    rm -rf "$work/$name"
    "$@" --out "$work/$name" > "$work/runs/$name.sim.log" 2>&1 || {
      echo "error: vio_sim failed for $name (see $work/runs/$name.sim.log)" >&2
      exit 1
    }
  fi
}

# field LOG PATTERN SED: the value of the first line matching PATTERN.
field() { grep -m1 "$2" "$1" | sed -E "$3" || true; }

printf '| run | imu | cameras | ATE rmse [m] | RPE 1 m rmse [m] | resets | solver median / p95 [ms CPU] | real time |\n'
printf '| --- | --- | --- | --- | --- | --- | --- | --- |\n'
# run NAME FOLDER IMU CAMERAS CONFIG: replays and prints one table row; sets
# last_ate, last_rpe and last_resets (empty when the row was not run or failed).
run() {
  local name="$1" folder="$2" imu="$3" cameras="$4" config="$5"
  last_ate="" last_rpe="" last_resets=""
  echo "$name" | grep -Eq "$only" || return 0
  local log="$work/runs/$name.log" noise=config
  [ "$imu" = synthetic ] && noise=sequence
  if ! "$replay" "$folder" --config "$config" --imu-noise "$noise" \
      --out "$work/runs/$name" > "$log" 2>&1; then
    printf '| %s | %s | %s | failed (see %s) | | | | |\n' "$name" "$imu" \
      "$cameras" "$log"
    return 0
  fi
  local ate rpe resets solver rt
  ate=$(field "$log" "ATE (posyaw)" 's/.*rmse ([0-9.]+) m.*/\1/')
  rpe=$(field "$log" "RPE (1 m)" 's/.*rmse ([0-9.]+) m.*/\1/')
  resets=$(field "$log" "^  resets" 's/^  resets *([0-9]+).*/\1/')
  solver=$(field "$log" "solver time per step" \
    's/.*median ([0-9.]+) ms, p95 ([0-9.]+) ms.*/\1 \/ \2/')
  rt=$(grep -a "^  wall time" "$log" | tail -n1 |
    sed -E 's/.*: ([0-9.]+)x real time.*/\1x/' || true)
  printf '| %s | %s | %s | %s | %s | %s | %s | %s |\n' "$name" "$imu" \
    "$cameras" "${ate:-n/a}" "${rpe:-n/a}" "${resets:-n/a}" \
    "${solver:-n/a}" "${rt:-n/a}"
  last_ate="$ate" last_rpe="$rpe" last_resets="$resets"
}

# mean_row NAME IMU CAMERAS RUNS ATES RPES RESETS: the row of the mean over
# RUNS seeds (ATES, RPES: space-separated figures; RESETS: their sum).
mean_row() {
  local name="$1" imu="$2" cameras="$3" runs="$4" ates="$5" rpes="$6"
  local resets="$7"
  mean() { awk '{ s = 0; for (i = 1; i <= NF; ++i) s += $i;
                  printf "%.4f", s / NF }' <<< "$1"; }
  printf '| %s | %s | %s | %s | %s | %s | mean of %s seeds | |\n' "$name" \
    "$imu" "$cameras" "$(mean "$ates")" "$(mean "$rpes")" "$resets" "$runs"
}

for preset in "$root"/config/sim_*.yaml; do
  name="sim_$(basename "$preset" .yaml | sed 's/^sim_//')"
  echo "$name" | grep -Eq "$only" || continue
  make_folder "$name" "$sim" --config "$preset"
  if grep -Eq '^  stereo: true' "$preset"; then
    run "$name" "$work/$name" synthetic stereo "$stereo_config"
  else
    run "$name" "$work/$name" synthetic mono "$mono_config"
  fi
done

for flight in "${flights[@]}"; do
  label="${flight%%:*}"
  folder="${flight#*:}"
  # variant: IMU, the curve vio_sim fits (ground-truth or imu), row suffix.
  variants=("synthetic:ground-truth:")
  [ "$curve" = imu ] || variants+=("recorded:ground-truth:")
  [ "$curve" = ground-truth ] || variants+=("recorded:imu:_imucurve")
  for variant in "${variants[@]}"; do
    IFS=: read -r imu fit suffix <<< "$variant"
    base="${label}_${imu}${suffix}"
    # One stereo folder per seed serves both replays (mono uses its cam0).
    for cameras in mono stereo; do
      config="$mono_config"
      [ "$cameras" = stereo ] && config="$stereo_config"
      ates="" rpes="" resets=0 runs=0
      for seed in "${seed_list[@]}"; do
        name="$base" seed_args=()
        if [ "$seed" != 1 ]; then
          name="${name}_seed${seed}"
          seed_args=(--seed "$seed")
        fi
        echo "${name}_${cameras}" | grep -Eq "$only" || continue
        make_folder "$name" "$sim" --config "$root/config/sim_stereo.yaml" \
          --flight "$folder" --imu "$imu" --curve "$fit" "${seed_args[@]}"
        run "${name}_${cameras}" "$work/$name" "$imu" "$cameras" "$config"
        if [ -n "$last_ate" ] && [ -n "$last_rpe" ]; then
          ates+=" $last_ate" rpes+=" $last_rpe"
          resets=$((resets + ${last_resets:-0})) runs=$((runs + 1))
        fi
      done
      if [ "${#seed_list[@]}" -gt 1 ] && [ "$runs" -gt 0 ]; then
        mean_row "${base}_${cameras}_mean" "$imu" "$cameras" "$runs" \
          "$ates" "$rpes" "$resets"
      fi
    done
  done
done
