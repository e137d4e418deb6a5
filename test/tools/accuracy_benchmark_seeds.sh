#!/bin/sh
# scripts/accuracy_benchmark.sh's seeds (--seeds) and mean rows, on stand-in
# tools: a vio_sim that writes its --seed into the folder and a vio_replay
# that prints figures made from it (ATE 0.01 * 2^(seed-1) m, RPE 0.005 * seed
# m, seed - 1 resets), so that the rows and their means are known exactly.
# Also the default curve (imu) and the errors of bad --seeds.
#
# usage: accuracy_benchmark_seeds.sh SOURCE_DIR WORK_DIR
set -u
source_dir=$1
work=$2
rm -rf "$work" && mkdir -p "$work/build/tools" || exit 1
cat > "$work/build/tools/vio_sim" <<'SIM'
#!/bin/sh
seed=1 out= curve=
while [ $# -gt 0 ]; do
  case "$1" in
    --seed) seed=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --curve) curve=$2; shift 2 ;;
    *) shift ;;
  esac
done
mkdir -p "$out/mav0" && echo "$seed" > "$out/seed" && echo "$curve" > "$out/curve"
SIM
cat > "$work/build/tools/vio_replay" <<'REPLAY'
#!/bin/sh
seed=$(cat "$1/seed")
awk -v s="$seed" 'BEGIN {
  printf "  resets      %d\n", s - 1
  printf "  solver time per step  median 1.00 ms, p95 2.00 ms, max 3.00 ms\n"
  printf "  ATE (posyaw)  rmse %.4f m, max 0.1 m\n", 0.01 * 2 ^ (s - 1)
  printf "  RPE (1 m)     rmse %.4f m, rotation rmse 0.1 deg\n", 0.005 * s
  printf "  wall time   1.00 s for 10.00 s of data: 10.0x real time\n" }'
REPLAY
chmod +x "$work/build/tools/vio_sim" "$work/build/tools/vio_replay"

bench=$source_dir/scripts/accuracy_benchmark.sh
bash "$bench" --build "$work/build" --only "V1_01_recorded" \
  > "$work/table.md" 2> "$work/stderr.txt"
echo "default: status $?"
# The rows, the figures only (name, ATE, RPE, resets).
awk -F' [|] ' 'NR > 2 { print $1 " " $4 " " $5 " " $6 }' "$work/table.md" |
  sed 's/^| //'
echo "curve: $(cat "$work/build/accuracy_benchmark/V1_01_recorded_imucurve_seed3/curve")"
bash "$bench" --build "$work/build" --only "V1_01_recorded_imucurve_seed2_mono" \
  --seeds 2 > "$work/one.md" 2>&1
echo "one seed: status $? rows $(grep -c '^| V1_01' "$work/one.md")"
bash "$bench" --build "$work/build" --seeds 1,x > /dev/null 2> "$work/bad.txt"
echo "bad seeds: status $?"
cat "$work/bad.txt"
