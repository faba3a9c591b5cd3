#!/bin/sh
# A mode stream or mode vtrees session over TCP on loopback for the CLI
# cases (cases.txt fields cannot hold ';' or '|', so the loop lives here):
#   replay_loopback.sh BIN TMP MODE FILE.lbk K [client options...]
# (MODE: stream or vtrees; SERVER:CLIENT, such as vtrees:stream, runs the
# clients in another mode than the server, to see them refuse each other:
# then the server's expected error goes to stdout, the clients' to stderr)
# starts `lodbake-replay FILE.lbk --mode MODE --serve 0 --clients K`, waits
# for the address on its first stdout line, runs K clients at once with
# `--mode MODE --connect ADDRESS [client options]`, waits for all of them
# and the server,
# then prints the clients' reports and the server's (stdout) and their
# errors (stderr). Exit: the first failing client's status, else the
# server's. The server gives up by itself when a client never comes (its
# accept timeout); a server that never prints its address is killed.
bin=$1
tmp=$2
mode=$3
lbk=$4
clients=$5
shift 5
server_mode=${mode%%:*}
client_mode=${mode##*:}
"$bin/lodbake-replay" "$lbk" --mode "$server_mode" --serve 0 --clients "$clients" \
  > "$tmp/server.out" 2> "$tmp/server.err" &
server=$!
tries=0
while [ ! -s "$tmp/server.out" ]; do
  tries=$((tries + 1))
  if [ "$tries" -gt 200 ] || ! kill -0 "$server" 2> /dev/null; then
    cat "$tmp/server.err" >&2
    echo "replay_loopback.sh: the server printed no address" >&2
    kill "$server" 2> /dev/null
    exit 4
  fi
  sleep 0.05
done
address=$(head -n 1 "$tmp/server.out")
pids=""
c=1
while [ "$c" -le "$clients" ]; do
  "$bin/lodbake-replay" --mode "$client_mode" --connect "$address" "$@" \
    > "$tmp/client$c.out" 2> "$tmp/client$c.err" &
  pids="$pids $!"
  c=$((c + 1))
done
status=0
for pid in $pids; do
  wait "$pid"
  rc=$?
  if [ "$status" -eq 0 ]; then status=$rc; fi
done
wait "$server"
server_status=$?
c=1
while [ "$c" -le "$clients" ]; do
  cat "$tmp/client$c.out"
  cat "$tmp/client$c.err" >&2
  c=$((c + 1))
done
cat "$tmp/server.out"
if [ "$server_mode" = "$client_mode" ]; then
  cat "$tmp/server.err" >&2
else
  cat "$tmp/server.err"
fi
if [ "$status" -ne 0 ]; then exit "$status"; fi
exit "$server_status"
