#!/bin/sh
# vio_replay on faulted copies of an 8 s simulated sequence (the issue-18
# table, docs/robustness.md): a repeated IMU line is warned about and the run
# goes on (status 0), --strict refuses it (status 1); an IMU that stops at
# 1.5 s leaves most frames without a pose (status 4, with the reason).
#
# usage: vio_replay_faults.sh VIO_SIM VIO_REPLAY SOURCE_DIR WORK_DIR
set -u
sim=$1
replay=$2
source_dir=$3
work=$4
imu=mav0/imu0/data.csv
rm -rf "$work" && mkdir -p "$work" || exit 1
sed 's/^duration_s: 40/duration_s: 8/' "$source_dir/config/sim_default.yaml" \
  > "$work/short.yaml"
"$sim" --config "$work/short.yaml" --out "$work/seq" > /dev/null || exit 1

copy() {  # copy NAME SED-EXPRESSION: seq with its IMU file edited
  cp -r "$work/seq" "$work/$1" && sed "$2" "$work/seq/$imu" > "$work/$1/$imu"
}

copy repeat '988p'
"$replay" "$work/repeat" --out "$work/out_repeat" > "$work/repeat.log" 2>&1
echo "repeat: status $?"
grep -o 'warning: .*data.csv:989: 1 exact repeat.*' "$work/repeat.log"
"$replay" "$work/repeat" --strict --out "$work/out_strict" 2>&1
echo "strict: status $?"

copy stops '302,$d'
"$replay" "$work/stops" --out "$work/out_stops" > "$work/stops.log"
echo "stops: status $?"
grep -o 'warning: IMU gap from .*' "$work/stops.log"
