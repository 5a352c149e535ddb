#!/usr/bin/env bash
# rocking_study in 3 shards, run by scripts/study_parallel.sh (GNU parallel) and by
# scripts/study_slurm.sbatch (an array job, Slurm's variables set by hand: no Slurm here), then merged:
# both give the bytes of one run (test/tools/expected/study_small_grid.sha256, as
# study_byte_identical.sh). summary.results is summary.json without its "run" block.
#   study_sharded_byte_identical.sh ROCKING_STUDY RECORDS_DIR EXPECTED_SHA256 SCRIPTS_DIR
set -u
study=$1
records=$2
expected=$3
scripts=$4
if [ ! -f "$records/MANIFEST.csv" ]; then
  echo "NOTICE: $records/MANIFEST.csv not found: the byte-identity check needs the shared records; skipped"
  exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=(--records "$records" --heights 3 --widths 2 --eccentricities 0.5,0.3 --only kobe_1995 --only northridge_1994 --exact-trig)
check() {  # check DIR WHAT
  /usr/bin/python3 -c "import json,sys;d=json.load(open(sys.argv[1]));d.pop('run');print(json.dumps(d,sort_keys=True))" \
      "$1/summary.json" | tr -d '\n' > "$1/summary.results"
  (cd "$1" && sha256sum -c "$expected") || { echo "FAIL: $2: merged output differs from $expected"; exit 1; }
}
ROCKING_STUDY=$study PARALLEL_OPTS="-j 2" bash "$scripts/study_parallel.sh" 3 "$tmp/parallel" "${args[@]}" > /dev/null 2>&1 \
  || { echo "FAIL: study_parallel.sh exited $?"; exit 1; }
check "$tmp/parallel/all" "GNU parallel"
for k in 1 2 3; do
  OUT=$tmp/slurm ROCKING_STUDY=$study SLURM_ARRAY_TASK_ID=$k SLURM_ARRAY_TASK_COUNT=3 SLURM_CPUS_PER_TASK=1 \
    bash "$scripts/study_slurm.sbatch" "${args[@]}" > /dev/null 2>&1 || { echo "FAIL: array task $k exited $?"; exit 1; }
done
OUT=$tmp/slurm ROCKING_STUDY=$study MERGE=1 SHARDS=3 bash "$scripts/study_slurm.sbatch" > /dev/null 2>&1 \
  || { echo "FAIL: the merge job exited $?"; exit 1; }
check "$tmp/slurm/all" "Slurm array"
echo ok
