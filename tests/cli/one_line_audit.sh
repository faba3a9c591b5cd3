#!/bin/sh
# one_line_audit.sh BIN BAD_DIR BAD_TABLE TMP: every file of the shared bad/
# folder through every tool that takes a mesh, with default options. A run
# either succeeds with at most one note line on stderr (no warning, no
# error), or fails with exactly one line, "TOOL: error: FILE: ...", and
# leaves no output. Every tool ends the way lodbake-pack does in BAD_TABLE
# (tests/cli/bad_inputs.txt, column 2): the same exit code, so a file one
# tool takes is taken by all of them. lodbake-inspect, the linter, reports
# what it can read: it fails where `inspect --strict` (column 4) exits 3.
set -u
bin=$1
bad=$2
table=$3
tmp=$4
rm -rf "$tmp"
mkdir -p "$tmp"
grep -v '^[[:space:]]*#' "$table" | grep '|' | while IFS='|' read -r file expected regex lint; do
  file=$(echo "$file" | tr -d '[:space:]')
  expected=$(echo "$expected" | tr -d '[:space:]')
  lint=$(echo "$lint" | tr -d '[:space:]')
  for run in "pack|-o|$tmp/o.lbk" "simplify|-o|$tmp/o.obj|--ratio|0.5" "simplify|--pm|$tmp/o.lbk" \
             "hierarchy|-o|$tmp/o.lbk" "fan|-o|$tmp/o.lbk" "strips|-o|$tmp/o.lbk" \
             "strips|--strips-only|-o|$tmp/o.lbk" "inspect"; do
    tool=lodbake-${run%%|*}
    args=$(echo "$run" | cut -s -d'|' -f2- | tr '|' ' ')
    # shellcheck disable=SC2086  # args holds no spaces but the separators
    "$bin/$tool" "$bad/$file" $args > "$tmp/out" 2> "$tmp/err"
    rc=$?
    lines=$(wc -l < "$tmp/err")
    problem=""
    want=$expected
    if [ "$tool" = lodbake-inspect ]; then
      want=0
      [ "$lint" = 3 ] && want=3
    fi
    if [ "$rc" -ne "$want" ]; then problem="exit $rc, expected $want"; fi
    if [ "$rc" -eq 0 ]; then
      if [ "$lines" -gt 1 ]; then problem="$problem; $lines stderr lines on success"; fi
      if grep -q -e ': error: ' -e ': warning: ' "$tmp/err"; then
        problem="$problem; a warning or error on success"
      fi
    else
      if [ "$lines" -ne 1 ]; then problem="$problem; $lines stderr lines on failure"; fi
      if ! grep -q "^$tool: error: $bad/$file: " "$tmp/err"; then
        problem="$problem; the line does not name the tool and the file"
      fi
      if [ -e "$tmp/o.lbk" ] || [ -e "$tmp/o.obj" ]; then problem="$problem; output left behind"; fi
    fi
    if [ -n "$problem" ]; then
      echo "FAIL $file $tool $args: $problem"
      sed 's/^/    /' "$tmp/err"
      echo x >> "$tmp/failures"
    fi
    rm -f "$tmp/o.lbk" "$tmp/o.obj"
  done
done
if [ -e "$tmp/failures" ]; then
  echo "$(wc -l < "$tmp/failures") runs broke the one-line rule"
  exit 1
fi
echo "every bad file: one line or none per run, the same outcome in every tool"
