#!/bin/bash
# make test-cluster: a single-node Slurm on loopback (munged, slurmctld and
# slurmd, each with its own socket, state and log under WORK, on ports
# 16817-16818 so a real Slurm on the machine is left alone), the Snakemake
# workflow submitted through workflow/profiles/slurm, and its files compared
# byte for byte with lodbake-bake's on the same recipe. Every daemon it
# started is stopped by its pid on exit. On failure it names the stage that
# failed and prints that stage's log.
#
#   slurm_workflow.sh TOOLS SOURCE DATA WORK
set -u
tools=$(realpath "$1") src=$(realpath "$2") data=$(realpath "$3") work=$4
rm -rf "$work" && mkdir -p "$work" && work=$(realpath "$work")
stage=setup
fail() {
  echo "test-cluster: FAILED at '$stage': $1" >&2
  [ $# -ge 2 ] && [ -f "$2" ] && { echo "--- $2 (last 30 lines):" >&2; tail -n 30 "$2" >&2; }
  exit 1
}
stop() {
  for daemon in slurmd slurmctld munged; do
    [ -f "$work/$daemon.pid" ] || continue
    pid=$(cat "$work/$daemon.pid")
    kill "$pid" 2> /dev/null || continue
    # slurmctld saves its state before it ends: wait, so that a rerun finds
    # the ports free.
    for _ in $(seq 20); do kill -0 "$pid" 2> /dev/null || break; sleep 0.5; done
  done
}
trap stop EXIT

for tool in munged mungekey slurmctld slurmd sbatch srun scontrol snakemake; do
  command -v $tool > /dev/null || fail "$tool missing (Debian's slurm-wlm, munge, snakemake)"
done

stage="munge key and munged"
mungekey --create --keyfile="$work/munge.key" > "$work/mungekey.log" 2>&1 \
  || fail "mungekey could not create a key" "$work/mungekey.log"
chmod 600 "$work/munge.key"
munged --force --socket="$work/munge.socket" --key-file="$work/munge.key" \
  --pid-file="$work/munged.pid" --log-file="$work/munged.log" --seed-file="$work/munged.seed" \
  > "$work/munged.out" 2>&1 || fail "munged did not start" "$work/munged.log"
echo probe | munge --socket="$work/munge.socket" | unmunge --socket="$work/munge.socket" \
  > "$work/unmunge.log" 2>&1 || fail "munge could not encode and decode a credential" "$work/unmunge.log"

stage="slurm.conf"
mkdir -p "$work/state" "$work/spool"
cpus=$(nproc)
memory=$(awk '/MemTotal/ { print int($2 / 1024 / 2) }' /proc/meminfo)
host=$(hostname -s)
cat > "$work/slurm.conf" <<CONF
ClusterName=lodbake
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=$(id -un)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge.socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
# Without accounting, Snakemake follows jobs with scontrol, which forgets a
# finished job after MinJobAge (300 s by default).
MinJobAge=3600
NodeName=lodbake1 NodeAddr=127.0.0.1 NodeHostname=$host CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=batch Nodes=lodbake1 Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf

stage=slurmctld
slurmctld -c -i > "$work/slurmctld.out" 2>&1 || fail "slurmctld did not start" "$work/slurmctld.log"
stage=slurmd
slurmd -N lodbake1 > "$work/slurmd.out" 2>&1 || fail "slurmd did not start" "$work/slurmd.log"
stage="node idle"
for _ in $(seq 30); do
  sinfo -h -N -o '%T' > "$work/sinfo.out" 2>&1 && grep -q idle "$work/sinfo.out" && break
  sleep 1
done
grep -q idle "$work/sinfo.out" \
  || { cat "$work/sinfo.out" >> "$work/slurmctld.log"; fail "the node is not idle after 30 s (sinfo: $(cat "$work/sinfo.out"))" "$work/slurmd.log"; }
stage="a plain sbatch job"
sbatch -W -o "$work/probe.out" --wrap="hostname" > "$work/sbatch.log" 2>&1 \
  || fail "sbatch --wrap=hostname failed" "$work/sbatch.log"

stage="the workflow through workflow/profiles/slurm"
# Snakemake 7.21 guesses the Slurm account from sacct -u "$USER" and fails
# with a KeyError when USER is unset (containers, cron).
export USER=${USER:-$(id -un)}
cp "$src/tests/cli/bake/workflow.toml" "$work/recipe.toml"
cd "$work" || fail "cd $work"
snakemake -s "$src/workflow/Snakefile" --profile "$src/workflow/profiles/slurm" \
  --config recipe=recipe.toml out=snake bake="$tools/lodbake-bake" set="src=$src,data=$data" \
  > snake.log 2>&1 || fail "snakemake --profile slurm failed" "$work/snake.log"
grep -q "submitted with SLURM jobid" snake.log || fail "no job went through Slurm" "$work/snake.log"

stage="byte for byte against lodbake-bake"
"$tools/lodbake-bake" recipe.toml --set "src=$src" --set "data=$data" --out bake --no-cache --quiet \
  > /dev/null 2> bake.err || fail "lodbake-bake failed" "$work/bake.err"
(cd bake && find . -type f | sort) > bake.files
(cd snake && find . -type f | sort) > snake.files
[ "$(wc -l < bake.files)" = 23 ] || fail "lodbake-bake wrote $(wc -l < bake.files) files, not 23"
diff bake.files snake.files > files.diff || fail "not the same files" "$work/files.diff"
while read -r file; do
  cmp "bake/$file" "snake/$file" > /dev/null || fail "$file differs"
done < bake.files
echo "test-cluster: $(grep -c 'submitted with SLURM jobid' snake.log) Slurm jobs wrote the same 23 files as lodbake-bake"
