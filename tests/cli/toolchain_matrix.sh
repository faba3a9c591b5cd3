#!/bin/sh
# toolchain_matrix.sh BIN MESH TMP matrix|pipeline [nodraco]
#
# nodraco: the tools were built without the Draco section codec; the Draco
# repackings are left out (the nodraco_ CLI cases check that they refuse).
#
# Every tool reads what every tool writes (docs/tools.md "One toolchain").
#
# pipeline: the chain a build step runs with default options: pack MESH,
#   simplify --pm, hierarchy (from the PM), fan, strips and strips
#   --strips-only, all merged by pack (compact, then --draco), validated and
#   replayed in every mode with --validate (sets: 1% of the LoDs, linearly
#   spaced; --validate checks each recovered LoD against the progressive mesh,
#   which takes minutes at the default 1..20% on the larger meshes).
# matrix: producers (pack, simplify --pm, hierarchy, fan, strips, strips
#   --strips-only, and the container merged from all of them) x repacking
#   (none, the default compact codecs, --draco, --quantize 14, --error-bits
#   8, --raw) x every consumer that applies (inspect --validate, --extract
#   with and without --lod, hierarchy, strips, every replay mode with
#   --validate). Every cell must succeed. A consumer's result from a
#   losslessly repacked file (compact, raw) must equal its result from the
#   file as written, byte for byte (replay rows without their timings);
#   after --error-bits the extracted meshes must still be equal, after
#   --quantize 14 and --draco their triangles equal and every coordinate
#   within 2^-13 of the mesh's extent (14-bit quantization moves a
#   coordinate by at most half a step, extent / (2^14 - 1) / 2).
set -u
bin=$1
mesh=$2
tmp=$3
mode=$4
draco=${5:-draco}
rm -rf "$tmp"
mkdir -p "$tmp"
failed=0
cells=0

# run LABEL COMMAND...: the command must exit 0; stderr is kept in $tmp/err.
run() {
  label=$1
  shift
  cells=$((cells + 1))
  "$@" > "$tmp/out" 2> "$tmp/err"
  rc=$?
  if [ "$rc" -ne 0 ]; then
    echo "FAIL $label: exit $rc"
    sed 's/^/  /' "$tmp/err"
    failed=1
    return 1
  fi
  return 0
}

fail() {
  echo "FAIL $1"
  failed=1
}

# Replay rows without the columns that are timings (*_ms, *_us).
untimed() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) keep[i] = ($i !~ /_(ms|us)$/) }
           { line = ""; for (i = 1; i <= NF; i++) if (keep[i]) line = line $i ","; print line }' "$1"
}

# Two OBJ files (lodbake's writer: "v x y z" and "f a b c" lines) with the
# same faces and every coordinate within `tolerance` x the extent of the
# first one's bounding box.
close_meshes() {
  awk -v tolerance="$3" '
    FNR == NR { if ($1 == "v") { n++; x[n] = $2; y[n] = $3; z[n] = $4
                  for (k = 2; k <= 4; k++) { if (n == 1 || $k < lo[k]) lo[k] = $k
                                             if (n == 1 || $k > hi[k]) hi[k] = $k } }
                else if ($1 == "f") face[++f] = $0
                next }
    $1 == "v" { m++; d = ($2 - x[m]); if (d < 0) d = -d; if (d > worst) worst = d
                d = ($3 - y[m]); if (d < 0) d = -d; if (d > worst) worst = d
                d = ($4 - z[m]); if (d < 0) d = -d; if (d > worst) worst = d }
    $1 == "f" { g++; if (face[g] != $0) bad = 1 }
    END { extent = 0; for (k = 2; k <= 4; k++) if (hi[k] - lo[k] > extent) extent = hi[k] - lo[k]
          if (bad || m != n || g != f) { print "different vertices or faces"; exit 1 }
          if (worst > tolerance * extent) { print "moved by " worst " of extent " extent; exit 1 } }
  ' "$1" "$2"
}

tags() {
  "$bin/lodbake-inspect" "$1" 2> /dev/null | awk '/^  [A-Z][A-Z][A-Z][A-Z] / { print $1 }' | sort -u | tr '\n' ' '
}

has() {
  case " $(tags "$1") " in *" $2 "*) return 0 ;; esac
  return 1
}

# The producers, each reading the previous tools' outputs.
produce() {
  run "pack" "$bin/lodbake-pack" -q "$mesh" -o "$tmp/pack.lbk" &&
    run "simplify --pm" "$bin/lodbake-simplify" -q "$tmp/pack.lbk" --pm "$tmp/pm.lbk" &&
    run "hierarchy" "$bin/lodbake-hierarchy" -q "$tmp/pm.lbk" -o "$tmp/hier.lbk" &&
    run "fan" "$bin/lodbake-fan" -q "$tmp/pack.lbk" -o "$tmp/fan.lbk" &&
    run "strips" "$bin/lodbake-strips" -q "$tmp/pm.lbk" -o "$tmp/strips.lbk" &&
    run "strips --strips-only" "$bin/lodbake-strips" -q --strips-only "$tmp/pack.lbk" \
      -o "$tmp/stripo.lbk" &&
    run "pack (merge)" "$bin/lodbake-pack" -q --raw "$tmp/pack.lbk" "$tmp/pm.lbk" \
      "$tmp/hier.lbk" "$tmp/fan.lbk" "$tmp/strips.lbk" "$tmp/stripo.lbk" -o "$tmp/all.lbk"
}

# consume FILE OUTDIR: every consumer that applies to FILE, outputs in OUTDIR.
consume() {
  file=$1
  out=$2
  name=$(basename "$file")
  mkdir -p "$out"
  present=$(tags "$file")
  run "$name: inspect --validate" "$bin/lodbake-inspect" -q --validate "$file"
  run "$name: inspect --extract" "$bin/lodbake-inspect" -q "$file" --extract "$out/base.obj"
  case " $present " in *" VSPL "*)
    run "$name: inspect --extract --lod" "$bin/lodbake-inspect" -q "$file" --extract \
      "$out/lod.obj" --lod 0.5
    run "$name: strips" "$bin/lodbake-strips" -q "$file" -o "$out/strips.lbk"
    ;;
  esac
  run "$name: hierarchy" "$bin/lodbake-hierarchy" -q "$file" -o "$out/hier.lbk"
  for replay in vhier:VHIE stream:VHIE vtrees:VTRE dag:DAGE fan:FANH sets:SETS; do
    replay_mode=${replay%%:*}
    case " $present " in *" ${replay#*:} "*)
      if [ "$replay_mode" = sets ]; then
        extra="--percent 10 --spacing linear"
      else
        extra=""
      fi
      # shellcheck disable=SC2086
      run "$name: replay --mode $replay_mode --validate" "$bin/lodbake-replay" -q "$file" \
        --mode "$replay_mode" --validate --csv "$out/$replay_mode.csv" $extra
      ;;
    esac
  done
}

# same DIR_A DIR_B LABEL: every consumer output of B equals A's.
same() {
  for a in "$1"/*; do
    b="$2/$(basename "$a")"
    [ -e "$b" ] || { fail "$3: $(basename "$a") is missing"; continue; }
    case "$a" in
      *.csv) untimed "$a" > "$tmp/a.rows"; untimed "$b" > "$tmp/b.rows"
             cmp -s "$tmp/a.rows" "$tmp/b.rows" || fail "$3: $(basename "$a") rows differ" ;;
      *) cmp -s "$a" "$b" || fail "$3: $(basename "$a") differs" ;;
    esac
  done
}

if [ "$mode" = pipeline ]; then
  produce || exit 1
  packed=all_compact
  run "pack (compact)" "$bin/lodbake-pack" -q "$tmp/all.lbk" -o "$tmp/all_compact.lbk"
  if [ "$draco" = draco ]; then
    packed="$packed all_draco"
    run "pack --draco (merge)" "$bin/lodbake-pack" -q --draco "$tmp/all.lbk" -o "$tmp/all_draco.lbk"
  fi
  for file in $packed; do
    run "$file: inspect --validate" "$bin/lodbake-inspect" -q --validate "$tmp/$file.lbk"
    for replay_mode in vhier dag fan stream vtrees; do
      run "$file: replay --mode $replay_mode --validate" "$bin/lodbake-replay" -q \
        "$tmp/$file.lbk" --mode "$replay_mode" --validate
    done
    run "$file: replay --mode sets --validate" "$bin/lodbake-replay" -q "$tmp/$file.lbk" \
      --mode sets --validate --percent 1 --spacing linear
  done
  echo "$cells runs, $([ $failed = 0 ] && echo all passed || echo some FAILED)"
  exit $failed
fi

produce || exit 1
for producer in pack pm hier fan strips stripo all; do
  repacks="none compact q14 e8 raw"
  [ "$draco" = draco ] && repacks="$repacks draco"
  for repack in $repacks; do
    file="$tmp/${producer}_$repack.lbk"
    case $repack in
      none) cp "$tmp/$producer.lbk" "$file" ;;
      compact) run "$producer: pack" "$bin/lodbake-pack" -q "$tmp/$producer.lbk" -o "$file" ;;
      draco) run "$producer: pack --draco" "$bin/lodbake-pack" -q --draco "$tmp/$producer.lbk" -o "$file" ;;
      q14) run "$producer: pack --quantize 14" "$bin/lodbake-pack" -q --quantize 14 \
             "$tmp/$producer.lbk" -o "$file" ;;
      e8) run "$producer: pack --error-bits 8" "$bin/lodbake-pack" -q --error-bits 8 \
            "$tmp/$producer.lbk" -o "$file" ;;
      raw) run "$producer: pack --raw" "$bin/lodbake-pack" -q --raw "$tmp/$producer.lbk" -o "$file" ;;
    esac
    [ -e "$file" ] || continue
    consume "$file" "$tmp/out_${producer}_$repack"
  done
  ref="$tmp/out_${producer}_none"
  same "$ref" "$tmp/out_${producer}_compact" "$producer: compact"
  same "$ref" "$tmp/out_${producer}_raw" "$producer: raw"
  for obj in base.obj lod.obj; do
    [ -e "$ref/$obj" ] || continue
    cmp -s "$ref/$obj" "$tmp/out_${producer}_e8/$obj" || fail "$producer: error-bits 8: $obj differs"
    for lossy in q14 $([ "$draco" = draco ] && echo draco); do
      if ! why=$(close_meshes "$ref/$obj" "$tmp/out_${producer}_$lossy/$obj" 0.0001220703125); then
        fail "$producer: $lossy: $obj: $why"
      fi
    done
  done
done
echo "$cells cells, $([ $failed = 0 ] && echo all passed || echo some FAILED)"
exit $failed
