#!/usr/bin/env bash
# Fault-injection replays (issue 13, item 3; docs/robustness.md): simulates a
# sequence with a built-in preset, corrupts a copy of it in one way per row
# with vio_faults, replays each copy with vio_replay and prints a markdown
# table: what the estimator did (from the replay's warnings and summary),
# whether it recovered, poses N of M, ATE, exit status.
#
#   scripts/fault_table.sh [--build DIR] [--work DIR] [--duration S]
#                          [--stereo] [--keep]
#
#   --build DIR     the build folder holding tools/vio_sim, vio_faults and
#                   vio_replay (default build)
#   --work DIR      scratch folder (default a fresh mktemp -d, removed at the
#                   end unless --keep)
#   --duration S    length of the simulated sequence (default 12 s; the
#                   faults sit at 5 s)
#   --stereo        config/sim_stereo.yaml replayed with config/stereo.yaml
#                   (default: config/sim_default.yaml replayed with
#                   config/default.yaml, the built-in defaults)
#
# "Recovered" is yes when the replay exits 0, the last frame the IMU reaches
# has a pose and the ATE is within 2x the clean run's; otherwise no, and why.
# A replay that crashes (an exit status other than 0, 1 or 4) or prints a
# NaN (in its summary or its trajectory) is a FAILED row, and the script
# exits with status 1 after the table. Run from the repository root.
set -u

build=build
work=
duration=12
stereo=0
keep=0
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --duration) duration=$2; shift 2 ;;
    --stereo) stereo=1; shift ;;
    --keep) keep=1; shift ;;
    *) echo "usage: $0 [--build DIR] [--work DIR] [--duration S] [--stereo] [--keep]" >&2
       exit 1 ;;
  esac
done
for tool in vio_sim vio_faults vio_replay; do
  if [ ! -x "$build/tools/$tool" ]; then
    echo "error: $build/tools/$tool not built (vbuild build --target $tool)" >&2
    exit 1
  fi
done
if [ -z "$work" ]; then work=$(mktemp -d); else mkdir -p "$work"; fi
[ "$keep" = 1 ] || trap 'rm -rf "$work"' EXIT

if [ "$stereo" = 1 ]; then
  preset=config/sim_stereo.yaml
  base_config=config/stereo.yaml
else
  preset=config/sim_default.yaml
  base_config=config/default.yaml  # = the built-in defaults
fi
sed "s/^duration_s: .*/duration_s: $duration/" "$preset" > "$work/preset.yaml"
rm -rf "$work/clean"
"$build/tools/vio_sim" --config "$work/preset.yaml" --out "$work/clean" \
  > "$work/sim.log" || { echo "error: vio_sim failed" >&2; exit 1; }

# One row: a name, vio_faults' arguments ("" for the clean run) and, when a
# third field is there, a sed expression applied to the replay's
# configuration (a key the fault is replayed with).
rows=(
  "none (clean)|"
  "IMU dropout 0.1 s at 5 s|--fault imu-dropout --at 5 --duration 0.1"
  "IMU dropout 1 s at 5 s|--fault imu-dropout --at 5 --duration 1"
  "20 IMU lines duplicated at 5 s|--fault imu-duplicate --at 5 --count 20"
  "IMU sample 3 places out of order at 5 s|--fault imu-out-of-order --at 5 --count 3"
  "1 NaN gyroscope sample at 5 s|--fault imu-nan --at 5 --count 1"
  "accelerometer saturated: x pinned at full scale (176.52 m/s^2) for 0.2 s at 5 s|--fault accel-saturation --at 5 --duration 0.2 --value 176.52"
  "accelerometer clipped at +-9.4 m/s^2 (under its readings) for 1 s at 5 s|--fault accel-clipped --at 5 --duration 1 --value 9.4"
  "accelerometer bias jump 0.3 m/s^2 at 5 s|--fault accel-bias-jump --at 5 --value 0.3"
  "gyroscope bias jump 0.02 rad/s at 5 s|--fault gyro-bias-jump --at 5 --value 0.02"
  "30 % of frames without features, 5-7 s|--fault empty-frames --at 5 --duration 2 --fraction 0.3"
  "30 % outlier observations, 5-7 s|--fault outliers --at 5 --duration 2 --fraction 0.3"
  "50 % outlier observations, 5-7 s|--fault outliers --at 5 --duration 2 --fraction 0.5"
  "camera-IMU offset 20 ms, not configured|--fault time-offset --value 0.020"
  "camera-IMU offset 30 ms, not configured|--fault time-offset --value 0.030"
  "camera-IMU offset 20 ms, estimated online (estimate_time_offset: true)|--fault time-offset --value 0.020|s/^  estimate_time_offset: false/  estimate_time_offset: true/"
  "2 s camera blackout at 5 s|--fault camera-blackout --at 5 --duration 2"
  "frame rate halved from 5 s|--fault half-rate --at 5"
)

# The value after `key` on the summary line starting with `line`.
field() { grep -m1 -- "$1" "$2" | sed -n "s/.*$3 *\([-0-9.e+naif]*\).*/\1/p"; }

failed=0
clean_ate=
printf '| fault | what the estimator did | recovered | poses | ATE (m) | exit |\n'
printf '| --- | --- | --- | --- | --- | --- |\n'
i=0
for row in "${rows[@]}"; do
  i=$((i + 1))
  name=${row%%|*}
  rest=${row#*|}
  args=${rest%%|*}
  edit=
  [ "$rest" = "$args" ] || edit=${rest#*|}
  config="$work/config$i.yaml"
  sed "$edit" "$base_config" > "$config"
  seq="$work/clean"
  if [ -n "$args" ]; then
    seq="$work/fault$i"
    rm -rf "$seq"
    # shellcheck disable=SC2086 # the arguments are words on purpose
    if ! "$build/tools/vio_faults" --in "$work/clean" --out "$seq" $args \
        > "$work/faults$i.log" 2>&1; then
      printf '| %s | FAILED: vio_faults: %s | | | | |\n' "$name" \
        "$(grep -m1 error: "$work/faults$i.log")"
      failed=1
      continue
    fi
  fi
  log="$work/replay$i.log"
  out="$work/out$i"
  "$build/tools/vio_replay" "$seq" --config "$config" --out "$out" \
    > "$log" 2>&1
  status=$?

  what=()
  if [ "$status" != 0 ] && [ "$status" != 1 ] && [ "$status" != 4 ]; then
    what+=("CRASH: $(tail -n 1 "$log")")
    failed=1
  fi
  if grep -qi 'rmse *-\?nan\|ATE.*-\?nan' "$log" ||
     { [ -f "$out/trajectory.tum" ] && grep -qi nan "$out/trajectory.tum"; }; then
    what+=("NaN in the output")
    failed=1
  fi
  if [ "$status" = 1 ]; then
    what+=("refused: \`$(grep -m1 '^error:' "$log" | sed "s|$work/||g; s/^error: //")\`")
  fi
  # Counted skips and replacements, from the summary.
  dropped=$(field '^  imu input' "$log" 'input')
  if [ -n "$dropped" ] && [ "$dropped" != 0 ]; then
    what+=("$(grep -m1 '^  imu input' "$log" | sed 's/^  imu input *//; s/; 0 sample(s) outside.*//')")
  fi
  replaced=$(grep -m1 '^  imu input' "$log" | sed -n 's/.*; \([0-9]*\) sample(s) outside.*/\1/p')
  if [ -n "$replaced" ] && [ "$replaced" != 0 ]; then
    what+=("$replaced IMU sample(s) outside the range replaced")
  fi
  gaps=$(grep -m1 '^  imu gaps' "$log" | sed 's/^  imu gaps *//')
  case "$gaps" in
    ""|"0 short (integrated across); 0 long"*) ;;
    *) what+=("IMU gaps: $gaps") ;;
  esac
  visual=$(grep -m1 '^  poses' "$log" | sed -n 's/.*; \([0-9]*\) tracked on vision alone.*/\1/p')
  skipped=$(grep -m1 '^  frames ' "$log" | sed -n 's/.*skipped \([0-9]*\)).*/\1/p')
  if [ -n "$skipped" ] && [ "$skipped" != 0 ]; then
    what+=("$skipped frame(s) skipped")
  fi
  resets=$(grep -m1 '^  resets  ' "$log" | awk '{print $2}')
  if [ -n "$resets" ] && [ "$resets" != 0 ]; then
    causes=$(grep '^    at [0-9]* ns:' "$log" | sed 's/^    at \([0-9]*\) ns: /\1 /' |
      awk -v start="$(head -n 2 "$work/clean/mav0/imu0/data.csv" | tail -n 1 | cut -d, -f1)" \
        '{t = ($1 - start) / 1e9; $1 = ""; printf "%s%s at %.1f s", (NR > 1 ? ", " : ""), substr($0, 2), t}')
    what+=("$resets reset(s): $causes")
  fi
  outliers=$(grep -m1 'outliers removed:' "$log" | sed -n 's/.*outliers removed: \([0-9]*\) sightings.*/\1/p')
  [ -n "$args" ] || clean_outliers=$outliers
  # Named when the outlier test removed 20 % more than in the clean run.
  if [ -n "$outliers" ] && [ -n "${clean_outliers:-}" ] && [ -n "$args" ] &&
     [ $((outliers * 10)) -gt $((clean_outliers * 12)) ]; then
    what+=("$outliers outlier sightings removed (clean: $clean_outliers)")
  fi
  outside=$(grep -m1 'observations removed:' "$log" | sed -n 's/.*removed: \([0-9]*\) outside.*/\1/p')
  if [ -n "$outside" ] && [ "$outside" != 0 ]; then
    what+=("$outside observation(s) outside the image removed")
  fi
  [ -n "$visual" ] && [ "$visual" != 0 ] && what+=("$visual frame(s) placed on vision alone")
  [ "${#what[@]}" = 0 ] && what+=("nothing detected")

  poses=$(grep -m1 '^  poses' "$log" | sed -n 's/^  poses *\([0-9]* of [0-9]*\) frames.*/\1/p')
  ate=$(grep -m1 'ATE (posyaw)' "$log" | sed -n 's/.*rmse \([^ ]*\) m, max.*/\1/p')
  [ -n "$args" ] || clean_ate=$ate

  # Recovered: status 0, a pose for the last frame, ATE within 2x clean.
  recovered=yes
  # The last frame the IMU reaches (a camera offset moves the last frame
  # past the IMU's end: that frame cannot have a pose, whatever happened).
  imu_end=$(tail -n 1 "$seq/mav0/imu0/data.csv" | cut -d, -f1)
  last_frame=$(awk -F, -v e="$imu_end" '!/^#/ && $1 + 0 <= e + 0 { t = $1 "" } END { print t }' \
    "$seq/mav0/cam0/features.csv")
  last_pose=$( [ -f "$out/trajectory.tum" ] && tail -n 1 "$out/trajectory.tum" | awk '{print $1}')
  if [ "$status" != 0 ]; then
    recovered="no (exit $status)"
  elif [ -z "$last_pose" ] ||
       ! awk -v f="$last_frame" -v p="$last_pose" 'BEGIN { exit !(p >= f / 1e9 - 0.01) }'; then
    recovered="no (no pose for the last frame)"
  elif [ -n "$clean_ate" ] && [ -n "$ate" ] &&
       ! awk -v a="$ate" -v c="$clean_ate" 'BEGIN { exit !(a <= 2 * c) }'; then
    recovered="no (ATE over 2x clean)"
  fi
  [ -n "$args" ] || recovered="-"

  joined=$(printf '%s; ' "${what[@]}")
  printf '| %s | %s | %s | %s | %s | %s |\n' "$name" "${joined%; }" \
    "$recovered" "${poses:--}" "${ate:--}" "$status"
done
if [ "$failed" != 0 ]; then
  echo "error: a crash, a NaN or a failed fault above (FAILED rows)" >&2
  exit 1
fi
