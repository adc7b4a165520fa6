#!/usr/bin/env bash
# Sourced by the benchmark scripts: wait_idle waits until the machine is idle — at least 95 % of CPU
# time idle over 2 s (/proc/stat) — for at most IDLE_WAIT seconds (default 600), and says so if it
# never was.
wait_idle() {
  local tries=0 a b idle total i
  while [ $tries -lt $(( ${IDLE_WAIT:-600} / 2 )) ]; do
    read -ra a < /proc/stat; sleep 2; read -ra b < /proc/stat
    idle=$(( (b[4] + b[5]) - (a[4] + a[5]) ))
    total=0; for i in 1 2 3 4 5 6 7 8; do total=$(( total + b[i] - a[i] )); done
    [ $total -gt 0 ] && [ $(( 100 * idle / total )) -ge 95 ] && return 0
    tries=$((tries + 1))
  done
  echo "$(basename "$0"): the machine never became idle; timing anyway" >&2
}
