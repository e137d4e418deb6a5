#!/bin/sh
# vio_replay's pipelined image replay against --sequential on the real V1_01
# excerpt (stereo), with cam0's 40th image replaced by a file that is not an
# image: both runs skip and count it, and their outputs are byte-identical.
#
# usage: vio_replay_pipeline.sh VIO_REPLAY SOURCE_DIR DATA_DIR WORK_DIR
set -u
replay=$1
source_dir=$2
data=$3/euroc_V1_01_first5s/mav0
work=$4
rm -rf "$work" && mkdir -p "$work/seq/mav0/cam0/data" || exit 1
for f in imu0 cam1 state_groundtruth_estimate0 body.yaml; do
  ln -s "$data/$f" "$work/seq/mav0/$f" || exit 1
done
ln -s "$data/cam0/data.csv" "$data/cam0/sensor.yaml" "$work/seq/mav0/cam0/"
bad=$(sed -n '41p' "$data/cam0/data.csv" | cut -d, -f2 | tr -d '\r')
for png in "$data"/cam0/data/*.png; do
  ln -s "$png" "$work/seq/mav0/cam0/data/" || exit 1
done
rm "$work/seq/mav0/cam0/data/$bad" && echo "not a png" > "$work/seq/mav0/cam0/data/$bad"

config=$source_dir/config/euroc_stereo.yaml
"$replay" "$work/seq" --config "$config" --sequential --out "$work/seq_out" \
  > "$work/sequential.log" 2>&1
echo "sequential: status $?"
"$replay" "$work/seq" --config "$config" --queue-frames 2 \
  --out "$work/pipe_out" > "$work/pipelined.log" 2>&1
echo "pipelined: status $?"
grep -h -o 'cam0: 94 used; skipped: 0 missing, 1 unreadable' \
  "$work/sequential.log" "$work/pipelined.log"
cmp "$work/seq_out/states.csv" "$work/pipe_out/states.csv" &&
  cmp "$work/seq_out/trajectory.tum" "$work/pipe_out/trajectory.tum" &&
  echo "outputs identical: $(wc -l < "$work/pipe_out/states.csv") lines"
"$replay" "$work/seq" --queue-frames 0 2>&1
echo "queue 0: status $?"
