#!/bin/sh
# lodbake-simplify --memory-limit killed by SIGTERM or SIGINT removes its
# work folder (.lodbake-work-PID beside -o), writes no output and ends by
# the signal (exit status 128 + its number): killed while it cuts the mesh
# into blocks, and once block files exist. MESH must take a few seconds at
# LIMIT (the full dragon, which the tests reassemble, at 16M: 30 blocks).
#
#   out_of_core_signal.sh TOOLS WORK MESH LIMIT
set -eu
tools=$1 work=$2 mesh=$3 limit=$4
[ -f "$mesh" ] || { echo "out_of_core_signal: no $mesh" >&2; exit 1; }
simplify=$tools/lodbake-simplify
fail() { echo "out_of_core_signal: $*" >&2; exit 1; }

# run NAME SIGNAL STATUS WAIT_FOR: starts a run, waits until its work folder
# holds WAIT_FOR (empty: the folder itself), sends SIGNAL, checks the rest.
run() {
  dir=$work/$1
  rm -rf "$dir" && mkdir -p "$dir"
  # A background job of a script starts with SIGINT ignored (and keeps it
  # ignored); env gives the tool the default disposition.
  env --default-signal=INT "$simplify" "$mesh" -o "$dir/out.ply" --ratio 0.01 \
    --memory-limit "$limit" --quiet 2> "$dir/err.txt" &
  pid=$!
  folder=$dir/.lodbake-work-$pid
  i=0
  until [ -e "$folder/$4" ]; do
    i=$((i + 1))
    [ $i -le 1200 ] || { kill -KILL $pid; fail "$1: no $folder/$4 after 60 s"; }
    kill -0 $pid 2> /dev/null || fail "$1: the run ended before $4 appeared"
    sleep 0.05
  done
  kill -"$2" $pid
  status=0
  wait $pid || status=$?
  [ $status -eq "$3" ] || fail "$1: exit status $status, expected $3"
  [ ! -e "$folder" ] || fail "$1: $folder is left: $(ls -A "$folder" | head -5)"
  [ ! -e "$dir/out.ply" ] || fail "$1: an output was written"
  [ "$(ls -A "$dir")" = "err.txt" ] || fail "$1: files left: $(ls -A "$dir")"
}

run term_split TERM 143 ""
run term_blocks TERM 143 block_0000.in
run int_blocks INT 130 block_0001.in
echo "out_of_core_signal: ok"
