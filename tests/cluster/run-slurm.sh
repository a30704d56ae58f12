#!/usr/bin/env bash
# The README's cluster path, run for real (docs/cluster.md): stand up a one-node SLURM cluster
# on this Debian machine with Debian's packages, run the quick configuration through
# workflow/profiles/slurm as docs/cluster.md tells a cluster user, check that every job ran
# as planned (each `sim run` its own SLURM job, all completed) and that the report came out,
# then stop the daemons it started.
#
#   sudo tests/cluster/run-slurm.sh [--workdir DIR] [--reference RESULTS] [--timeout MINUTES]
#
#   --workdir DIR        where this checkout is copied and run, with its Python environment,
#                        the cluster's state and the logs (default: $TMPDIR/sim-slurm-test or
#                        /tmp/sim-slurm-test); emptied first, kept afterwards for inspection
#   --reference RESULTS  results/ of a local quick run of the same sources: every netCDF file
#                        of the cluster run must hold the same data
#   --timeout MINUTES    give up on the workflow after this long (default 90)
#
# Needs root, apt-get, Python >= 3.11 with venv, and access to Debian's and Python's package
# indexes. About 20 minutes on 2 cores shared with other work: 2-3 for the Python environment,
# 2-3 for the warm-up, 12-18 for the workflow.
set -euo pipefail

say() { printf '\n== %s\n' "$*"; }
die() {
    printf 'run-slurm.sh: %s\n' "$*" >&2
    exit 1
}

REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
WORKDIR=${TMPDIR:-/tmp}/sim-slurm-test
REFERENCE=""
TIMEOUT_MIN=90
while (($#)); do
    case $1 in
    --workdir) WORKDIR=${2:?--workdir needs a directory}; shift 2 ;;
    --reference) REFERENCE=${2:?--reference needs a directory}; shift 2 ;;
    --timeout) TIMEOUT_MIN=${2:?--timeout needs minutes}; shift 2 ;;
    -h | --help) sed -n '2,19p' "$0"; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
    esac
done

# ---------------------------------------------------------------- refuse what we cannot do
[[ $(id -u) -eq 0 ]] || die "needs root: it installs packages and starts SLURM's daemons (try: sudo $0)"
command -v apt-get >/dev/null || die "needs apt-get (Debian or Ubuntu): SLURM and munge come from its packages"
for daemon in slurmctld slurmd; do
    if pgrep -x "$daemon" >/dev/null; then
        die "a $daemon is already running; this script starts its own cluster and leaves" \
            "an existing one alone (if an interrupted run of this script left it:" \
            "kill \$(cat $WORKDIR/slurm/$daemon.pid))"
    fi
done
SLURM_CONF_FILE=/etc/slurm/slurm.conf
MARK="# one-node test cluster of sim's tests/cluster/run-slurm.sh"
if [[ -e $SLURM_CONF_FILE ]] && [[ $(head -n1 "$SLURM_CONF_FILE") != "$MARK" ]]; then
    die "$SLURM_CONF_FILE exists and was not written by this script; not touching a real cluster's configuration"
fi
if [[ -n $REFERENCE ]]; then
    [[ -d $REFERENCE ]] || die "--reference $REFERENCE is not a directory"
    REFERENCE=$(cd "$REFERENCE" && pwd)
fi
WORKDIR=$(realpath -m "$WORKDIR")
case $WORKDIR/ in "$REPO"/*) die "--workdir must lie outside the checkout ($REPO)" ;; esac
mkdir -p "$WORKDIR"
if [[ -n $(ls -A "$WORKDIR") ]] && [[ ! -e $WORKDIR/.sim-slurm-test ]]; then
    die "$WORKDIR is not empty and not a previous work directory of this script; choose another --workdir"
fi

# ---------------------------------------------------------------- install
say "Installing SLURM and munge (Debian packages)"
PACKAGES=(slurm-wlm munge rsync python3-venv)
missing=()
for package in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]})); then
    apt-get update -q
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
else
    echo "already installed: ${PACKAGES[*]}"
fi
python3 -c 'import sys; sys.exit(sys.version_info < (3, 11))' || die "needs Python >= 3.11 as python3"

# ---------------------------------------------------------------- the project, as a user has it
say "Copying the checkout to $WORKDIR/project"
find "$WORKDIR" -mindepth 1 -delete
touch "$WORKDIR/.sim-slurm-test"
PROJECT=$WORKDIR/project
SLURM_DIR=$WORKDIR/slurm
mkdir -p "$PROJECT" "$SLURM_DIR/state" "$SLURM_DIR/spool"
rsync -a --exclude /.venv --exclude /.venv-ci --exclude /results --exclude /logs \
    --exclude /.snakemake --exclude /report.html --exclude /report.zip --exclude __pycache__ \
    --exclude .pytest_cache --exclude .ruff_cache --exclude '*.egg-info' "$REPO"/ "$PROJECT"/
cd "$PROJECT"

say "Python environment (docs/cluster.md, step 1)"
python3 -m venv .venv
# shellcheck disable=SC1091
. .venv/bin/activate
python -m pip install --quiet -r requirements.txt
python -m pip install --quiet --no-deps -e .

# ---------------------------------------------------------------- configure and start SLURM
STARTED_MUNGE=false
stop_cluster() {
    local status=$?
    set +e
    say "Stopping the cluster"
    if [[ -e $SLURM_DIR/slurmctld.pid ]]; then
        local left
        left=$(squeue -h -o %i 2>/dev/null)
        if [[ -n $left ]]; then
            echo "cancelling SLURM jobs still queued or running: $left"
            # shellcheck disable=SC2086
            scancel $left
            sleep 5
        fi
    fi
    local pidfile pid
    for pidfile in "$SLURM_DIR/slurmd.pid" "$SLURM_DIR/slurmctld.pid"; do
        [[ -s $pidfile ]] || continue
        pid=$(cat "$pidfile")
        kill "$pid" 2>/dev/null && echo "stopped ${pidfile##*/} ($pid)"
        for _ in $(seq 30); do kill -0 "$pid" 2>/dev/null || break; sleep 1; done
        kill -9 "$pid" 2>/dev/null
    done
    if $STARTED_MUNGE && [[ -s /run/munge/munged.pid ]]; then
        pid=$(cat /run/munge/munged.pid)
        kill "$pid" 2>/dev/null && echo "stopped munged ($pid)"
    fi
    if [[ $(head -n1 "$SLURM_CONF_FILE" 2>/dev/null) == "$MARK" ]]; then
        rm -f "$SLURM_CONF_FILE"
    fi
    exit "$status"
}
trap stop_cluster EXIT
trap 'exit 130' INT TERM

say "Configuring a one-node cluster"
# the node as slurmd detects it (CPUs, sockets, cores, threads, memory), on the loopback address
NODE=$(slurmd -C | head -n1)
[[ $NODE == NodeName=* ]] || die "slurmd -C did not describe this node: $NODE"
HOST=${NODE%% *}
HOST=${HOST#NodeName=}
cat >"$SLURM_CONF_FILE" <<EOF
$MARK
# (removed again when it ends). No accounting database: job states come from squeue (the
# profile's slurm-status-command), SLURM's record of finished jobs from the job completion log.
ClusterName=simtest
SlurmctldHost=$HOST(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
StateSaveLocation=$SLURM_DIR/state
SlurmdSpoolDir=$SLURM_DIR/spool
SlurmctldPidFile=$SLURM_DIR/slurmctld.pid
SlurmdPidFile=$SLURM_DIR/slurmd.pid
SlurmctldLogFile=$SLURM_DIR/slurmctld.log
SlurmdLogFile=$SLURM_DIR/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/filetxt
JobCompLoc=$SLURM_DIR/jobcomp.log
# SLURM's default: squeue lists a finished job for 300 s
MinJobAge=300
ReturnToService=2
$NODE NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=compute Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
cp "$SLURM_CONF_FILE" "$SLURM_DIR/slurm.conf"


say "Starting munge, slurmctld and slurmd"
if ! munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
    install -d -o munge -g munge -m 0755 /run/munge
    runuser -u munge -- /usr/sbin/munged
    STARTED_MUNGE=true
fi
slurmctld
slurmd
for _ in $(seq 60); do
    [[ $(sinfo -h -o %t 2>/dev/null) == idle ]] && break
    sleep 1
done
[[ $(sinfo -h -o %t 2>/dev/null) == idle ]] || die "the node did not come up; see $SLURM_DIR/slurmctld.log and slurmd.log"
sinfo
SLURM_VERSION=$(sinfo --version)

# ---------------------------------------------------------------- run as docs/cluster.md says
say "Warm-up: compiling the numba kernels once into the shared cache (docs/cluster.md, step 2)"
export NUMBA_CACHE_DIR=$PROJECT/.snakemake/numba
start=$SECONDS
sim run sixbar -q -o "$WORKDIR/warmup.nc" --set simulation.revolutions=0.01 --set bodies.rod2.kind=beam
rm -f "$WORKDIR/warmup.nc"
WARMUP_S=$((SECONDS - start))
echo "warm-up: ${WARMUP_S} s; $(find "$NUMBA_CACHE_DIR" -name '*.nbc' | wc -l) compiled kernels cached"

PROFILE=(--workflow-profile workflow/profiles/slurm)
QUICK=(--configfile config/quick.yaml)
snakemake -n "${PROFILE[@]}" "${QUICK[@]}" >"$WORKDIR/plan.txt" 2>&1 ||
    die "dry run failed; see $WORKDIR/plan.txt"

say "Running the quick configuration through SLURM (log: $WORKDIR/snakemake.log)"
start=$SECONDS
status=0
timeout "${TIMEOUT_MIN}m" snakemake "${PROFILE[@]}" "${QUICK[@]}" >"$WORKDIR/snakemake.log" 2>&1 || status=$?
WALL_S=$((SECONDS - start))
tail -n 3 "$WORKDIR/snakemake.log"
if ((status == 124)); then
    die "the workflow did not finish within $TIMEOUT_MIN minutes (job states not seen?); see $WORKDIR/snakemake.log"
elif ((status != 0)); then
    die "the workflow failed (exit $status); see $WORKDIR/snakemake.log and .snakemake/slurm_logs/"
fi

say "Report"
snakemake --report report.html "${QUICK[@]}" >"$WORKDIR/report.log" 2>&1 ||
    die "the report failed; see $WORKDIR/report.log"

# ---------------------------------------------------------------- verify
say "Checking the run against the plan and SLURM's records"
VERIFY=(--plan "$WORKDIR/plan.txt" --log "$WORKDIR/snakemake.log"
    --jobcomp "$SLURM_DIR/jobcomp.log" --project "$PROJECT")
[[ -n $REFERENCE ]] && VERIFY+=(--reference "$REFERENCE")
verified=0
python tests/cluster/verify.py "${VERIFY[@]}" | tee "$WORKDIR/verify.txt" || verified=$?

{
    echo "SLURM:                 $SLURM_VERSION; $NODE"
    echo "snakemake:             $(python -c 'from importlib.metadata import version as v; print(v("snakemake"))')"
    echo "executor plugin:       snakemake-executor-plugin-slurm $(python -c 'from importlib.metadata import version as v; print(v("snakemake-executor-plugin-slurm"))')"
    echo "warm-up:               ${WARMUP_S} s"
    echo "workflow wall time:    $((WALL_S / 60)) min $((WALL_S % 60)) s"
    grep '^jobs planned' "$WORKDIR/verify.txt" || true
    echo "report:                $PROJECT/report.html ($(stat -c %s "$PROJECT/report.html") bytes)"
    if [[ -n $REFERENCE ]]; then
        grep 'netCDF files' "$WORKDIR/verify.txt" | sed 's/^\(ok\|FAIL\) *//; s/^/compared:              /' || true
    fi
} >"$WORKDIR/summary.txt"
say "Summary (also in $WORKDIR/summary.txt)"
cat "$WORKDIR/summary.txt"
((verified == 0)) || die "some checks failed; see $WORKDIR/verify.txt"
echo "all checks passed"
