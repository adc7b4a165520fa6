#!/usr/bin/env bash
# A sharded sweep on a real one-node Slurm cluster, checked against the unsharded run.
#
#   SHADOWLAB_BIN=target/debug/shadowlab bash tests/slurm/run.sh
#
# In a fresh temporary directory (removed on exit) it writes `shadowlab sweep --example` as the
# spec, runs it unsharded into U/, then brings up munged, slurmctld and slurmd on localhost (as
# root, with every file, socket, port and log of their own under the temporary directory; no
# systemd, no cgroups), lets `shadowlab sweep --slurm --shards 4` write the job array and the
# dependent merge job, submits them with the generated submit.sh and waits for both. The merged
# result must equal the unsharded one, timings aside: results.csv without its `*_ms` columns,
# report.md up to its `## Time` section, every SVG byte for byte, the same files. Where Slurm cannot
# be brought up (not root, a daemon does not start, the node never becomes idle) it prints
# `SKIP real Slurm: <reason>` and runs the 4 shards itself as background processes into one
# directory, then `shadowlab merge`, and checks the same things.
#
# Every daemon it starts is stopped on exit, failure or interrupt (by the pids it recorded; any job
# process left behind is found by a marker variable in its environment). Output: one line per
# check, `ok - ...` or `not ok - ...`, diagnostics prefixed `# `, and last `N passed, M failed`;
# the exit status is non-zero if any check failed.
#
# Environment:
#   SHADOWLAB_BIN                  the shadowlab binary (required, except in the self-test)
#   SHADOWLAB_REQUIRE_SLURM=1      a Slurm that cannot be brought up is a failure, not a SKIP
#                                  (the fallback still runs)
#   SHADOWLAB_SLURM_SKIP=1         do not try Slurm; run the fallback only
#   SHADOWLAB_SLURM_SELFTEST=1     no shadowlab: bring the cluster up, run a 4-task job array and a
#                                  job depending on it, check their outputs, tear down
#   SHADOWLAB_SLURM_KEEP=1         keep the temporary directory (daemons are stopped all the same)
#   SHADOWLAB_SLURM_UP_TIMEOUT     seconds for the node to become idle (30)
#   SHADOWLAB_SLURM_JOB_TIMEOUT    seconds for the jobs to finish (300)
#   SHADOWLAB_STEP_TIMEOUT         seconds for one shadowlab command (600)
# shellcheck disable=SC2317 # functions called through check() look unreachable to shellcheck
set -euo pipefail

SHARDS=4
UP_TIMEOUT=${SHADOWLAB_SLURM_UP_TIMEOUT:-30}
JOB_TIMEOUT=${SHADOWLAB_SLURM_JOB_TIMEOUT:-300}
STEP_TIMEOUT=${SHADOWLAB_STEP_TIMEOUT:-600}
SELFTEST=${SHADOWLAB_SLURM_SELFTEST:-0}

# The daemons live in /usr/sbin, which a non-login PATH may lack.
PATH="$PATH:/usr/sbin:/sbin"
# A caller's Slurm settings (running inside a job of another cluster, SQUEUE_FORMAT, ...) must not
# leak into this cluster's commands.
while IFS= read -r name; do
  case "$name" in SLURM_* | SBATCH_* | SALLOC_* | SRUN_* | SQUEUE_* | SINFO_* | SCONTROL_*) unset "$name" ;; esac
done < <(compgen -e)

PASSED=0
FAILED=0
SUMMARY_PRINTED=0
ok() { PASSED=$((PASSED + 1)); echo "ok - $*"; }
not_ok() { FAILED=$((FAILED + 1)); echo "not ok - $*"; }
diag() { sed 's/^/# /' >&2; }
note() { echo "# $*" >&2; }
# check WHAT COMMAND...: one check from a command's exit status (errexit does not apply inside).
check() {
  local what=$1
  shift
  if "$@"; then ok "$what"; else not_ok "$what"; fi
}
summary() {
  SUMMARY_PRINTED=1
  echo "$PASSED passed, $FAILED failed"
}

if [[ $SELFTEST != 1 ]]; then
  if [[ -z ${SHADOWLAB_BIN:-} ]]; then
    echo "tests/slurm/run.sh: set SHADOWLAB_BIN to the shadowlab binary" >&2
    exit 2
  fi
  BIN=$(command -v -- "$SHADOWLAB_BIN" || true)
  if [[ -z $BIN || ! -x $BIN || -d $BIN ]]; then
    echo "tests/slurm/run.sh: SHADOWLAB_BIN=$SHADOWLAB_BIN is not an executable file" >&2
    exit 2
  fi
  BIN=$(readlink -f -- "$BIN") # absolute: the Slurm jobs and the shards run it from elsewhere
fi

PY=/usr/bin/python3
[[ -x $PY ]] || PY=$(command -v python3 || true)

# munged insists that every directory above its socket be searchable by all, so the temporary
# directory is 0711 (its contents keep their own, tighter modes).
WORK=$(mktemp -d "${TMPDIR:-/tmp}/shadowlab-slurm.XXXXXX")
chmod 0711 "$WORK"
RUN=$WORK/run # pid files of everything started here, and the daemons' logs
mkdir -p "$RUN" "$WORK/logs"
# Every process started from here on (daemons, job steps, jobs) carries this marker, so that
# teardown finds whatever a killed daemon left behind without matching processes by name.
export SHADOWLAB_SLURM_TEST_DIR="$WORK"
MARKER="SHADOWLAB_SLURM_TEST_DIR=$WORK"

BG_PIDS=()        # shards run by the fallback
SLURM_STARTED=0   # some daemon was started: teardown has work to do
SLURM_STOPPED=0

# --- processes ---------------------------------------------------------------------------------

# alive PID: the process exists and is not a zombie (our own daemons are children of this shell,
# and a dead child stays a zombie until waited for, which `kill -0` does not tell apart).
alive() {
  local stat rest
  [[ -n $1 && -r /proc/$1/stat ]] || return 1
  # (not $(< file): under errexit, bash 5.2 exits when that file has vanished, whatever follows)
  { read -r stat <"/proc/$1/stat"; } 2>/dev/null || return 1
  rest=${stat##*) }
  [[ ${rest%% *} != Z ]]
}

# stop PID NAME: SIGTERM, up to 10 s, then SIGKILL; reaps it if it is our child.
stop_pid() {
  local pid=$1 name=$2 i
  alive "$pid" || { wait "$pid" 2>/dev/null || true; return 0; }
  kill -TERM "$pid" 2>/dev/null || true
  for ((i = 0; i < 100; i++)); do
    alive "$pid" || break
    sleep 0.1
  done
  if alive "$pid"; then
    note "$name (pid $pid) ignored SIGTERM for 10 s: SIGKILL"
    kill -KILL "$pid" 2>/dev/null || true
    for ((i = 0; i < 50; i++)); do
      alive "$pid" || break
      sleep 0.1
    done
  fi
  wait "$pid" 2>/dev/null || true
}

# Processes carrying this run's marker, other than this shell.
marked_pids() {
  local dir pid
  for dir in /proc/[0-9]*; do
    pid=${dir#/proc/}
    [[ $pid == "$$" || $pid == "${BASHPID:-}" ]] && continue
    alive "$pid" || continue
    grep -qzxF -- "$MARKER" "$dir/environ" 2>/dev/null && echo "$pid"
  done
  return 0
}

# start_daemon NAME COMMAND...: in the foreground mode of the daemon, in the background here, so that
# its pid is known at once (written to $RUN/NAME.pid before anything else can fail).
start_daemon() {
  local name=$1
  shift
  "$@" </dev/null >"$RUN/$name.out" 2>&1 &
  echo "$!" >"$RUN/$name.pid"
  SLURM_STARTED=1
}

pid_of() { [[ -s $RUN/$1.pid ]] && cat "$RUN/$1.pid"; }

# Stops everything this run started: the jobs (while slurmd can still end their steps), slurmd,
# slurmctld, munged, the fallback's shards, then anything left carrying the marker. Idempotent.
teardown() {
  local pid i ids name
  local -a seen
  # Job steps that are ending by themselves now become zombies of init once they exit; wait below
  # until they are gone from the process table altogether.
  mapfile -t seen < <(marked_pids)
  for pid in "${BG_PIDS[@]}"; do stop_pid "$pid" shard; done
  BG_PIDS=()
  if ((SLURM_STARTED)) && ((!SLURM_STOPPED)); then
    SLURM_STOPPED=1
    if alive "$(pid_of slurmctld)"; then
      ids=$(timeout 10 squeue -h -o %A 2>/dev/null | tr '\n' ' ' || true)
      if [[ -n ${ids// /} ]]; then
        note "cancelling jobs still queued: $ids"
        # shellcheck disable=SC2086 # a list of job ids
        timeout 10 scancel $ids 2>/dev/null || true
        for ((i = 0; i < 30; i++)); do
          [[ -z $(timeout 5 squeue -h -o %A 2>/dev/null || true) ]] && break
          sleep 0.5
        done
      fi
    fi
    for name in slurmd slurmctld munged; do
      pid=$(pid_of "$name" || true)
      [[ -n $pid ]] && stop_pid "$pid" "$name"
    done
  fi
  # From here on, commands started by this shell must not carry the marker themselves.
  unset SHADOWLAB_SLURM_TEST_DIR SLURM_CONF
  for pid in $(marked_pids); do
    note "left behind: pid $pid $(tr '\0' ' ' <"/proc/$pid/cmdline" 2>/dev/null || true)"
    stop_pid "$pid" leftover
  done
  for pid in "${seen[@]}"; do
    for ((i = 0; i < 50; i++)); do
      [[ -e /proc/$pid ]] || break
      sleep 0.1
    done
  done
  # A job step that ended before the scan above is already a zombie, whose environment cannot be
  # read; init reaps it within a second or two. Only waited for (up to 5 s), never signalled.
  if ((SLURM_STARTED)); then
    for ((i = 0; i < 50; i++)); do
      zombie_steps || break
      sleep 0.1
    done
  fi
}

# Some slurmstepd is a zombie waiting for init (pid 1) to reap it.
zombie_steps() {
  local dir stat
  for dir in /proc/[0-9]*; do
    { read -r stat <"$dir/stat"; } 2>/dev/null || continue
    [[ $stat == *"(slurmstepd) Z 1 "* ]] && return 0
  done
  return 1
}

on_exit() {
  local rc=$?
  set +e
  trap - EXIT INT TERM HUP
  teardown
  if ((!SUMMARY_PRINTED)); then
    not_ok "the test ran to its end (it stopped early, exit status $rc)"
    summary
  fi
  if [[ ${SHADOWLAB_SLURM_KEEP:-0} == 1 ]]; then
    echo "# kept $WORK" >&2
  else
    rm -rf -- "$WORK"
  fi
  if ((FAILED > 0 && rc == 0)); then rc=1; fi
  exit "$rc"
}
trap on_exit EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
trap 'exit 129' HUP

dump_slurm_logs() {
  local f
  for f in "$WORK/munge/munged.log" "$RUN/munged.out" "$RUN/slurmctld.log" "$RUN/slurmctld.out" \
    "$RUN/slurmd.log" "$RUN/slurmd.out"; do
    [[ -s $f ]] || continue
    echo "--- last lines of $f" | diag
    tail -n 15 "$f" | diag
  done
}

# --- the cluster -------------------------------------------------------------------------------

SKIP_REASON=
# The last fatal (else error) line of a daemon's output, for the SKIP reason.
last_error() {
  local line
  line=$(cat "$@" 2>/dev/null | grep -i 'fatal' | tail -n 1 || true)
  [[ -n $line ]] || line=$(cat "$@" 2>/dev/null | grep -i 'error' | grep -v 'pmix\|MPI' | tail -n 1 || true)
  echo "${line:-no error logged}"
}
skip_because() {
  SKIP_REASON=$1
  return 1
}

# Two free TCP ports in 20000-29999, below Linux's ephemeral range.
free_ports() {
  if [[ -n $PY ]]; then
    "$PY" - <<'EOF'
import random, socket
ports = []
for _ in range(200):
    port = random.randrange(20000, 30000)
    if port in ports:
        continue
    s = socket.socket()
    try:
        s.bind(("", port))
    except OSError:
        continue
    finally:
        s.close()
    ports.append(port)
    if len(ports) == 2:
        print(*ports)
        break
EOF
  else
    local base=$((20000 + ($$ % 4999) * 2))
    echo "$base $((base + 1))"
  fi
}

# Brings up munged, slurmctld and slurmd; returns 1 with SKIP_REASON set where it cannot.
slurm_up() {
  local cmd node conf hw ports ctld_port d_port i state sock
  [[ $(id -u) == 0 ]] || skip_because "not root (the daemons run as root here)" || return 1
  for cmd in munged slurmctld slurmd sbatch squeue sinfo scontrol scancel; do
    command -v "$cmd" >/dev/null || skip_because "$cmd not found (apt-get install slurm-wlm munge)" || return 1
  done
  node=$(hostname -s 2>/dev/null || uname -n)
  node=${node%%.*}
  [[ $node =~ ^[A-Za-z0-9][A-Za-z0-9_-]*$ ]] || skip_because "unusable short host name '$node'" || return 1

  # munge: a fresh key only root can read (munged runs as root here), its own socket, pid file,
  # seed and log. The key's directory is 0700; the socket's must be searchable by all.
  mkdir -p "$WORK/munge" "$WORK/sock"
  chmod 0700 "$WORK/munge"
  chmod 0755 "$WORK/sock"
  sock=$WORK/sock/munge.socket
  ((${#sock} < 100)) || skip_because "munge socket path too long: $sock" || return 1
  if command -v mungekey >/dev/null; then
    mungekey --create --keyfile="$WORK/munge/munge.key" >/dev/null 2>&1 ||
      skip_because "mungekey --create failed" || return 1
  else
    dd if=/dev/urandom of="$WORK/munge/munge.key" bs=1024 count=1 status=none ||
      skip_because "could not write a munge key" || return 1
  fi
  chown root:root "$WORK/munge/munge.key"
  chmod 0400 "$WORK/munge/munge.key"
  start_daemon munged munged --foreground --socket="$sock" --key-file="$WORK/munge/munge.key" \
    --pid-file="$WORK/sock/munged.pid" --seed-file="$WORK/munge/munged.seed" \
    --log-file="$WORK/munge/munged.log"
  for ((i = 0; i < 100; i++)); do
    [[ -S $sock ]] && break
    alive "$(pid_of munged)" || break
    sleep 0.1
  done
  [[ -S $sock ]] ||
    { dump_slurm_logs; skip_because "munged did not start ($(last_error "$RUN/munged.out"))"; } || return 1
  if command -v munge >/dev/null && command -v unmunge >/dev/null; then
    timeout 10 munge -n -S "$sock" 2>/dev/null | timeout 10 unmunge -S "$sock" >/dev/null 2>&1 ||
      { dump_slurm_logs; skip_because "munge cannot encode and decode a credential"; } || return 1
  fi

  # Slurm: the node as slurmd -C sees it, under its real short name (slurmctld only runs where
  # SlurmctldHost names this host) but at 127.0.0.1, whatever the name resolves to.
  hw=$(timeout 20 slurmd -C 2>/dev/null | grep -m1 '^NodeName=' || true)
  if [[ -n $hw ]]; then
    hw=${hw#NodeName=* }
  else
    hw="CPUs=$(nproc)"
  fi
  ports=$(free_ports || true)
  read -r ctld_port d_port <<<"$ports"
  [[ -n ${d_port:-} ]] || skip_because "no free TCP port found" || return 1
  mkdir -p "$WORK/slurm/state" "$WORK/slurm/spool"
  conf=$WORK/slurm/slurm.conf
  : >"$WORK/slurm/plugstack.conf" # none of /etc/slurm/plugstack.conf.d's SPANK plugins
  cat >"$conf" <<EOF
# One node on localhost, for tests/slurm/run.sh; every path under $WORK.
ClusterName=shadowlabtest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
StateSaveLocation=$WORK/slurm/state
SlurmdSpoolDir=$WORK/slurm/spool
SlurmctldPidFile=$RUN/slurmctld.daemon.pid
SlurmdPidFile=$RUN/slurmd.daemon.pid
SlurmctldLogFile=$RUN/slurmctld.log
SlurmdLogFile=$RUN/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
PlugStackConfig=$WORK/slurm/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
MailProg=/bin/true
ReturnToService=2
SlurmdParameters=config_overrides
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
SchedulerParameters=kill_invalid_depend
MinJobAge=3600
InactiveLimit=0
KillWait=5
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$node NodeAddr=127.0.0.1 $hw State=UNKNOWN
PartitionName=debug Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF=$conf
  start_daemon slurmctld slurmctld -D -f "$conf"
  start_daemon slurmd slurmd -D -f "$conf" -N "$node"

  state=
  for ((i = 0; i < UP_TIMEOUT * 2; i++)); do
    alive "$(pid_of slurmctld)" ||
      { dump_slurm_logs; skip_because "slurmctld exited ($(last_error "$RUN/slurmctld.out" "$RUN/slurmctld.log"))"; } ||
      return 1
    alive "$(pid_of slurmd)" ||
      { dump_slurm_logs; skip_because "slurmd exited ($(last_error "$RUN/slurmd.out" "$RUN/slurmd.log"))"; } ||
      return 1
    state=$(timeout 5 sinfo -h -n "$node" -o %t 2>/dev/null || true)
    [[ $state == idle ]] && break
    sleep 0.5
  done
  [[ $state == idle ]] ||
    { dump_slurm_logs; skip_because "node $node not idle after ${UP_TIMEOUT} s (state: '${state:-none}')"; } ||
    return 1
  note "Slurm up: node $node ($hw), slurmctld port $ctld_port, slurmd port $d_port, in $((SECONDS - T_UP)) s"
}

# wait_jobs IDS: until squeue lists none of the jobs (comma-separated ids), at most JOB_TIMEOUT s.
wait_jobs() {
  local ids=$1 out rc start=$SECONDS last=-1
  while ((SECONDS - start < JOB_TIMEOUT)); do
    rc=0
    out=$(timeout 10 squeue -h -j "$ids" -o '%i %T %r' 2>&1) || rc=$?
    if ((rc == 0)) && [[ -z $out ]]; then return 0; fi
    if [[ $out == *"Invalid job id"* ]]; then return 0; fi # purged: long finished
    if [[ $out == *DependencyNeverSatisfied* ]]; then
      echo "$out" | diag
      return 1
    fi
    if (((SECONDS - start) / 15 != last)); then
      last=$(((SECONDS - start) / 15))
      note "after $((SECONDS - start)) s: $(paste -sd';' <<<"$out")"
    fi
    sleep 1
  done
  note "jobs $ids still queued after ${JOB_TIMEOUT} s:"
  timeout 10 squeue -j "$ids" 2>&1 | diag || true
  return 1
}

# job_states ID: one JobState per job record (an array job: one per task).
job_states() {
  timeout 10 scontrol -o show job "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2
}

# all_completed ID COUNT: exactly COUNT records, every one COMPLETED.
all_completed() {
  local states
  states=$(job_states "$1" || true)
  [[ $(grep -c . <<<"$states") == "$2" ]] && ! grep -qv '^COMPLETED$' <<<"$states"
}

# started_after FIRST SECOND: SECOND's StartTime is not before any EndTime of FIRST's records
# (Slurm's times are ISO 8601 to the second, so they compare as strings).
started_after() {
  local ends start
  ends=$(timeout 10 scontrol -o show job "$1" 2>/dev/null | grep -o 'EndTime=[^ ]*' | cut -d= -f2 | LC_ALL=C sort || true)
  start=$(timeout 10 scontrol -o show job "$2" 2>/dev/null | grep -o 'StartTime=[^ ]*' | cut -d= -f2 || true)
  note "$1 ended at: $(paste -sd' ' <<<"$ends"); $2 started at: $start"
  [[ -n $ends && $start == 20* && ! $start < $(tail -n 1 <<<"$ends") ]]
}

show_jobs() {
  local id
  for id in "$@"; do
    timeout 10 scontrol -o show job "$id" 2>&1 |
      grep -o 'JobId=[^ ]*\|ArrayTaskId=[^ ]*\|JobState=[^ ]*\|Reason=[^ ]*\|ExitCode=[^ ]*\|StdOut=[^ ]*' |
      paste -sd' ' | diag || true
  done
}

# --- the comparison ----------------------------------------------------------------------------

# The CSV comparisons, in Debian's Python without extra packages. `same A B`: the same rows in the
# same order; `union A B...`: A's rows are the rows of all the Bs together, order aside. Columns
# whose names end in `_ms` (timings) are left out of both.
write_csv_compare() {
  cat >"$WORK/csv_compare.py" <<'EOF'
import csv, sys

def load(path):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        sys.exit(f"{path}: {e.strerror}")
    if not rows:
        sys.exit(f"{path}: empty, not even a header")
    header = rows[0]
    keep = [i for i, name in enumerate(header) if not name.strip().endswith("_ms")]
    body = []
    for n, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            sys.exit(f"{path}:{n}: {len(row)} fields under a header of {len(header)}")
        body.append(tuple(row[i] for i in keep))
    return tuple(header[i] for i in keep), body

def show(row):
    text = ",".join(row)
    return text if len(text) <= 300 else text[:300] + "..."

mode, first, rest = sys.argv[1], sys.argv[2], sys.argv[3:]
header, rows = load(first)
if not rows:
    sys.exit(f"{first}: no rows")
other_rows = []
for path in rest:
    other_header, body = load(path)
    if other_header != header:
        sys.exit(f"{path}: columns (timings aside) differ from {first}:\n  {show(other_header)}\n  {show(header)}")
    other_rows += body
if mode == "union":
    rows, other_rows = sorted(rows), sorted(other_rows)
if len(rows) != len(other_rows):
    sys.exit(f"{len(other_rows)} rows in {' '.join(rest)}, {len(rows)} in {first}")
for n, (a, b) in enumerate(zip(rows, other_rows), start=1):
    if a != b:
        sys.exit(f"row {n} differs (timings aside):\n  {' '.join(rest)}: {show(b)}\n  {first}: {show(a)}")
print(f"{len(rows)} rows, {len(header)} columns compared (timings aside)")
EOF
}

csv_compare() {
  local out
  if [[ -z $PY ]]; then
    note "no python3 for the CSV comparison"
    return 1
  fi
  if out=$("$PY" "$WORK/csv_compare.py" "$@" 2>&1); then
    echo "$out" | diag
  else
    echo "$out" | diag
    return 1
  fi
}

files_of() { (cd "$1" && find . -type f | LC_ALL=C sort); }

same_files() {
  local a b
  [[ -d $1 && -d $2 ]] || return 1
  a=$(files_of "$1") b=$(files_of "$2")
  [[ $a == "$b" ]] && return 0
  diff <(echo "$a") <(echo "$b") | diag || true
  return 1
}

# report.md up to (not including) its `## Time` section: the timings.
report_head() { awk '/^## Time/ { exit } { print }' "$1"; }

same_report() {
  [[ -s $1/report.md && -s $2/report.md ]] || return 1
  [[ -n $(report_head "$1/report.md") ]] || { note "$1/report.md has nothing before ## Time"; return 1; }
  diff <(report_head "$1/report.md") <(report_head "$2/report.md") >"$WORK/report.diff" && return 0
  head -n 40 "$WORK/report.diff" | diag
  return 1
}

is_parquet() {
  [[ -s $1 ]] && [[ $(head -c 4 "$1") == PAR1 ]] && [[ $(tail -c 4 "$1") == PAR1 ]]
}

same_svgs() {
  local svg n=0 bad=0
  while IFS= read -r -d '' svg; do
    svg=${svg#"$1"/}
    n=$((n + 1))
    if ! cmp -s "$1/$svg" "$2/$svg"; then
      note "$svg differs"
      bad=$((bad + 1))
    fi
  done < <(find "$1" -type f -name '*.svg' -print0)
  note "$n SVG files compared, $bad differ"
  ((n > 0 && bad == 0))
}

cell_names() { (cd "$1/cells" && find . -maxdepth 1 -type f -name '*.json' | LC_ALL=C sort); }

same_cells() {
  [[ -d $1/cells && -d $2/cells ]] || return 1
  local a b
  a=$(cell_names "$1") b=$(cell_names "$2")
  note "$(grep -c . <<<"$a") cell files in $1/cells, $(grep -c . <<<"$b") in $2/cells"
  [[ -n $a && $a == "$b" ]]
}

shard_csvs() {
  local i
  for ((i = 0; i < SHARDS; i++)); do echo "$1/shard-$i-of-$SHARDS/results.csv"; done
}

all_shards_written() {
  local f missing=0
  while IFS= read -r f; do
    [[ -s $f ]] || { note "missing: $f"; missing=1; }
  done < <(shard_csvs "$1")
  ((!missing))
}

# compare_with_unsharded DIR LABEL: DIR's sweep (cells, shards, merged) against U.
compare_with_unsharded() {
  local dir=$1 label=$2 m=$1/merged u=$WORK/U/merged
  local -a shards
  check "$label: every shard wrote $dir/shard-I-of-$SHARDS/results.csv" all_shards_written "$dir"
  check "$label: the same cell files as the unsharded run" same_cells "$WORK/U" "$dir"
  mapfile -t shards < <(shard_csvs "$dir")
  check "$label: the shards' rows together are the unsharded run's rows (order and *_ms aside)" \
    csv_compare union "$WORK/U/shard-0-of-1/results.csv" "${shards[@]}"
  if [[ ! -d $m ]]; then
    not_ok "$label: $m written (nothing to compare)"
    return
  fi
  check "$label: merged/ has the same files as the unsharded merged/" same_files "$u" "$m"
  check "$label: merged results.csv equals the unsharded one (*_ms columns aside)" \
    csv_compare same "$u/results.csv" "$m/results.csv"
  check "$label: merged results.parquet is a Parquet file" is_parquet "$m/results.parquet"
  check "$label: merged report.md equals the unsharded one up to ## Time" same_report "$u" "$m"
  check "$label: every merged SVG is byte-identical to the unsharded one" same_svgs "$u" "$m"
}

# run_step NAME COMMAND...: a command with a time limit, its output to logs/NAME.log (tail shown on
# failure).
run_step() {
  local name=$1 rc=0 start=$SECONDS
  shift
  timeout --foreground "$STEP_TIMEOUT" "$@" >"$WORK/logs/$name.log" 2>&1 || rc=$?
  note "$name: exit $rc after $((SECONDS - start)) s"
  if ((rc != 0)); then
    tail -n 20 "$WORK/logs/$name.log" | diag
    ((rc == 124)) && note "$name: killed after ${STEP_TIMEOUT} s"
  fi
  return "$rc"
}

# --- the runs ----------------------------------------------------------------------------------

# The 4 shards as background processes of this shell into one directory, then the merge.
run_fallback() {
  local dir=$WORK/F i rc start=$SECONDS
  local -a pids=()
  mkdir -p "$dir"
  for ((i = 0; i < SHARDS; i++)); do
    timeout "$STEP_TIMEOUT" "$BIN" sweep "$WORK/spec.toml" --out "$dir" --shard "$i/$SHARDS" \
      >"$WORK/logs/shard-$i.log" 2>&1 &
    pids+=("$!")
    BG_PIDS+=("$!")
  done
  for ((i = 0; i < SHARDS; i++)); do
    rc=0
    wait "${pids[i]}" || rc=$?
    ((rc == 0)) || tail -n 20 "$WORK/logs/shard-$i.log" | diag
    check "fallback: shard $i/$SHARDS ran (exit $rc)" test "$rc" = 0
  done
  BG_PIDS=()
  note "fallback: $SHARDS shards in $((SECONDS - start)) s"
  if run_step merge "$BIN" merge "$dir" --out "$dir/merged"; then
    ok "fallback: shadowlab merge $dir --out $dir/merged"
    compare_with_unsharded "$dir" fallback
  else
    not_ok "fallback: shadowlab merge $dir --out $dir/merged"
  fi
}

merged_written() {
  [[ -s $1/results.csv && -s $1/results.parquet && -s $1/report.md ]] &&
    [[ -n $(find "$1" -name '*.svg' -print -quit) ]]
}
unsharded_written() {
  [[ -s $1/shard-0-of-1/results.csv && -n $(find "$1/cells" -name '*.json' -print -quit 2>/dev/null) ]]
}
no_cells() { [[ -z $(find "$1/cells" -name '*.json' -print -quit 2>/dev/null) ]]; }

# The sweep's own Slurm scripts on the cluster.
run_on_slurm() {
  local dir=$WORK/S array_id merge_id start rc=0
  if ! run_step slurm-scripts "$BIN" sweep "$WORK/spec.toml" --out "$dir" --slurm --shards "$SHARDS"; then
    not_ok "slurm: shadowlab sweep --slurm --shards $SHARDS wrote its scripts"
    return
  fi
  ok "slurm: shadowlab sweep --slurm --shards $SHARDS wrote its scripts"
  check "slurm: array.sbatch, merge.sbatch and submit.sh exist" \
    test -s "$dir/slurm/array.sbatch" -a -s "$dir/slurm/merge.sbatch" -a -s "$dir/slurm/submit.sh"
  check "slurm: array.sbatch is a job array --array=0-$((SHARDS - 1))" \
    grep -q -- "--array=0-$((SHARDS - 1))\b" "$dir/slurm/array.sbatch"
  check "slurm: sweep --slurm itself ran no cell" no_cells "$dir"

  (cd "$WORK" && timeout 60 bash "$dir/slurm/submit.sh") >"$WORK/logs/submit.out" 2>"$WORK/logs/submit.err" || rc=$?
  array_id=$(sed -n 1p "$WORK/logs/submit.out") merge_id=$(sed -n 2p "$WORK/logs/submit.out")
  array_id=${array_id%%;*} merge_id=${merge_id%%;*} # sbatch --parsable: ID[;CLUSTER]
  if ((rc != 0)) || [[ ! $array_id =~ ^[0-9]+$ || ! $merge_id =~ ^[0-9]+$ ]]; then
    cat "$WORK/logs/submit.out" "$WORK/logs/submit.err" | diag
    not_ok "slurm: submit.sh submitted two jobs and printed their ids (exit $rc)"
    return
  fi
  ok "slurm: submit.sh submitted two jobs and printed their ids (array $array_id, merge $merge_id)"

  start=$SECONDS
  check "slurm: the jobs finished within ${JOB_TIMEOUT} s" wait_jobs "$array_id,$merge_id"
  note "slurm: jobs done in $((SECONDS - start)) s"
  check "slurm: the $SHARDS array tasks COMPLETED" all_completed "$array_id" "$SHARDS"
  check "slurm: the merge job COMPLETED" all_completed "$merge_id" 1
  check "slurm: the merge job started after every array task ended" started_after "$array_id" "$merge_id"
  if ((FAILED > 0)); then
    show_jobs "$array_id" "$merge_id"
    # The jobs' output: sbatch's default (slurm-*.out in the submitting directory) or under S/.
    { find "$WORK" -maxdepth 1 -name 'slurm-*.out' -print0; find "$dir" -maxdepth 3 -name '*.out' -print0; } 2>/dev/null |
      while IFS= read -r -d '' f; do
        echo "--- $f" | diag
        tail -n 10 "$f" | diag
      done
  fi
  compare_with_unsharded "$dir" slurm
}

# The self-test: a 4-task job array, each task writing its id and times, and a job depending on it.
run_selftest() {
  local dir=$WORK/selftest array_id merge_id i ids overlap start
  mkdir -p "$dir"
  cat >"$dir/array.sbatch" <<'EOF'
#!/bin/bash
#SBATCH --array=0-3
#SBATCH --output=task-%a.out
start=$(date +%s.%N)
sleep 1
echo "$SLURM_ARRAY_TASK_ID $start $(date +%s.%N)" > "task-$SLURM_ARRAY_TASK_ID.txt"
EOF
  cat >"$dir/after.sbatch" <<'EOF'
#!/bin/bash
#SBATCH --output=after.out
echo "start $(date +%s.%N)" > after.txt
cat task-*.txt >> after.txt
EOF
  array_id=$(cd "$dir" && timeout 30 sbatch --parsable array.sbatch) || true
  array_id=${array_id%%;*}
  merge_id=$(cd "$dir" && timeout 30 sbatch --parsable --dependency="afterok:$array_id" after.sbatch) || true
  merge_id=${merge_id%%;*}
  if [[ ! $array_id =~ ^[0-9]+$ || ! $merge_id =~ ^[0-9]+$ ]]; then
    not_ok "selftest: sbatch submitted the array and the dependent job"
    return
  fi
  ok "selftest: sbatch submitted the array ($array_id) and the dependent job ($merge_id)"
  start=$SECONDS
  check "selftest: the jobs finished within ${JOB_TIMEOUT} s" wait_jobs "$array_id,$merge_id"
  note "selftest: jobs done in $((SECONDS - start)) s"
  check "selftest: the 4 array tasks COMPLETED" all_completed "$array_id" 4
  check "selftest: the dependent job COMPLETED" all_completed "$merge_id" 1
  check "selftest: Slurm started the dependent job after every task ended" started_after "$array_id" "$merge_id"
  ids=$(cat "$dir"/task-*.txt 2>/dev/null | cut -d' ' -f1 | sort -n | paste -sd' ' || true)
  check "selftest: each task wrote its SLURM_ARRAY_TASK_ID (got: $ids)" test "$ids" = "0 1 2 3"
  # Two 1-CPU tasks at once on 2 CPUs (CR_CPU), and the dependent job only after all of them.
  overlap=$(cat "$dir"/task-*.txt 2>/dev/null | awk '{ s[NR] = $2; e[NR] = $3 }
    END { n = 0; for (i in s) for (j in s) if (i < j && s[i] < e[j] && s[j] < e[i]) n++; print n }' || true)
  note "selftest: overlapping task pairs: $overlap"
  check "selftest: tasks ran side by side" test "${overlap:-0}" -ge 1
  # shellcheck disable=SC2016 # awk's fields
  check "selftest: the dependent job started after the tasks' last line" \
    awk 'NR == 1 { start = $2; next } $3 > start { bad = 1 } END { exit (NR == 5 && !bad) ? 0 : 1 }' \
    "$dir/after.txt"
  if ((FAILED > 0)); then
    show_jobs "$array_id" "$merge_id"
    tail -n 5 "$dir"/*.out 2>/dev/null | diag || true
  fi
}

# After teardown: nothing this run started is still running.
nothing_left() {
  local name pid left=0
  for name in munged slurmctld slurmd; do
    pid=$(pid_of "$name" || true)
    if [[ -n $pid ]] && alive "$pid"; then
      note "$name (pid $pid) still running"
      left=1
    fi
  done
  [[ -z $(marked_pids) ]] || { note "processes with the marker still running: $(marked_pids | paste -sd' ')"; left=1; }
  ((!left))
}

# The end of every run: stop what was started, check that nothing is left, the summary line. The
# exit status is set by on_exit from the failures.
finish() {
  teardown
  check "no daemon or job of this test left running" nothing_left
  summary
  exit 0
}

# --- main --------------------------------------------------------------------------------------

cd "$WORK"
T_UP=$SECONDS
write_csv_compare

if [[ $SELFTEST == 1 ]]; then
  if slurm_up; then
    ok "Slurm cluster up (munged, slurmctld, slurmd; node idle)"
    run_selftest
  else
    not_ok "Slurm cluster up: $SKIP_REASON"
  fi
  finish
fi

rc=0
timeout 60 "$BIN" sweep --example >"$WORK/spec.toml" 2>"$WORK/logs/example.err" || rc=$?
if ((rc != 0)) || [[ ! -s $WORK/spec.toml ]]; then
  tail -n 20 "$WORK/logs/example.err" | diag
  not_ok "shadowlab sweep --example printed a spec (exit $rc)"
  finish
fi
ok "shadowlab sweep --example printed a spec ($(wc -l <"$WORK/spec.toml") lines)"

if ! run_step unsharded "$BIN" sweep "$WORK/spec.toml" --out "$WORK/U"; then
  not_ok "unsharded sweep ran"
  finish
fi
ok "unsharded sweep ran"
check "unsharded: merged/ has results.csv, results.parquet, report.md and SVG plots" \
  merged_written "$WORK/U/merged"
check "unsharded: shard-0-of-1/results.csv and cells/*.json written" unsharded_written "$WORK/U"

T_UP=$SECONDS
if [[ ${SHADOWLAB_SLURM_SKIP:-0} == 1 ]]; then
  SKIP_REASON="SHADOWLAB_SLURM_SKIP=1"
  echo "SKIP real Slurm: $SKIP_REASON"
  run_fallback
elif slurm_up; then
  ok "Slurm cluster up (munged, slurmctld, slurmd; node idle)"
  run_on_slurm
else
  if [[ ${SHADOWLAB_REQUIRE_SLURM:-0} == 1 ]]; then
    not_ok "Slurm cluster up (SHADOWLAB_REQUIRE_SLURM=1): $SKIP_REASON"
  else
    echo "SKIP real Slurm: $SKIP_REASON"
  fi
  teardown # what did start of the cluster
  run_fallback
fi

finish
