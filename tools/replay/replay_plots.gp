# Paper-style charts of one lodbake-replay run (lodbake-replay --plot DIR).
# lodbake-replay writes this script into DIR with the variables below set
# in front of it, the per-frame rows (the --csv columns) as frames.csv, and
# runs gnuplot in DIR. Edit and re-run it there with `gnuplot replay.gp`.
#   mode   'vhier', 'dag', 'fan' or 'sets'
#   lanes  the dag traversals replayed, e.g. 'priority linear constant'
#   title  shown above every chart
# The charts are the papers': traversal time, accuracy and fronts per frame
# (Zheng & Chan 2006, Figures 6, 7 and 9), adapt operations per frame (Livny
# et al. 2007, Table 3 per frame), recovery time per LoD (Belmonte et al.
# 2006, Table 3 per LoD).

set terminal svg size 900,520 dynamic enhanced font 'sans,12' background rgb 'white'
set datafile separator ','
set grid
set key outside right top
set xlabel 'frame'
data = 'frames.csv'
lane_title(name) = name eq 'priority' ? 'priority-oriented' : (name eq 'constant' ? 'constant-time' : name)

if (mode eq 'dag') {
  # dag columns: frame,traversal,splits,collapses,visited,budget_mode,fs,fc,triangles,traversal_ms,accuracy
  # One row per frame and traversal, in the order of `lanes`: lane i's rows
  # are every L-th row from row i - 1.
  L = words(lanes)

  # The DAG paper's Figure 6.
  set output 'traversal_time.svg'
  set title title."\ntraversal time per frame"
  set ylabel 'traversal time (ms)'
  plot for [i=1:L] data skip 1 every L::(i - 1) using 1:10 \
    with lines lw 1.5 title lane_title(word(lanes, i))

  # Figure 7: share of the priority-oriented traversal's triangles.
  if (L > 1 || word(lanes, 1) ne 'priority') {
    set output 'accuracy.svg'
    set title title."\naccuracy against the priority-oriented traversal"
    set ylabel 'accuracy (%)'
    set yrange [0:100]
    plot for [i=1:L] data skip 1 every L::(i - 1) \
      using 1:(word(lanes, i) ne 'priority' ? 100 * column(11) : NaN) \
      with lines lw 1.5 title word(lanes, i) ne 'priority' ? lane_title(word(lanes, i)) : ''
    unset yrange
  }

  # Figure 9: the fronts against the mesh, for the first traversal.
  set output 'fronts.svg'
  set title title."\nfront sizes and mesh size (".lane_title(word(lanes, 1))." traversal)"
  set ylabel 'nodes / triangles'
  plot data skip 1 every L::0 using 1:9 with lines lw 1.5 title 'triangles', \
       data skip 1 every L::0 using 1:($7 + $8) with lines lw 1.5 title '|Fs| + |Fc|', \
       data skip 1 every L::0 using 1:7 with lines title '|Fs|', \
       data skip 1 every L::0 using 1:8 with lines title '|Fc|'

  set output 'operations.svg'
  set title title."\nmesh changes per frame"
  set ylabel 'operations'
  plot for [i=1:L] data skip 1 every L::(i - 1) using 1:3 \
         with lines lw 1.5 title lane_title(word(lanes, i)).' splits', \
       for [i=1:L] data skip 1 every L::(i - 1) using 1:4 \
         with lines dt 2 title lane_title(word(lanes, i)).' collapses'
} else {
if (mode eq 'fan') {
  # fan columns: frame,fan_merges,fan_splits,collapses,splits,active,triangles,adapt_ms
  set output 'adapt_time.svg'
  set title title."\nadapt time per frame"
  set ylabel 'adapt time (ms)'
  plot data skip 1 using 1:8 with lines lw 1.5 title 'dual-path adapt'

  set output 'fronts.svg'
  set title title."\nactive nodes and mesh size"
  set ylabel 'nodes / triangles'
  plot data skip 1 using 1:7 with lines lw 1.5 title 'triangles', \
       data skip 1 using 1:6 with lines lw 1.5 title 'active nodes'

  set output 'operations.svg'
  set title title."\nadapt operations per frame"
  set ylabel 'operations'
  plot data skip 1 using 1:2 with lines lw 1.5 title 'fan-merges', \
       data skip 1 using 1:3 with lines lw 1.5 title 'fan-splits', \
       data skip 1 using 1:4 with lines dt 2 title 'edge collapses (fine path)', \
       data skip 1 using 1:5 with lines dt 2 title 'vertex splits (fine path)'
} else {
if (mode eq 'sets') {
  # sets columns: spacing,percent,step,lod,strips,indices,triangles,fresh_us,coherent_us
  set output 'recovery_time.svg'
  set title title."\nrecovery time per LoD (every test, both directions)"
  set xlabel 'LoD (0 = full mesh)'
  set ylabel 'recovery time (us)'
  set logscale y
  plot for [sp in 'linear exponential'] data skip 1 \
         using 4:(strcol(1) eq sp ? column(8) : NaN) with points pt 7 ps 0.3 title sp.', fresh', \
       for [sp in 'linear exponential'] data skip 1 \
         using 4:(strcol(1) eq sp ? column(9) : NaN) with points pt 6 ps 0.3 title sp.', coherent'
  unset logscale y
} else {
  # vhier columns: frame,splits,collapses,passes,front,triangles,adapt_ms
  set output 'adapt_time.svg'
  set title title."\nadapt time per frame"
  set ylabel 'adapt time (ms)'
  plot data skip 1 using 1:7 with lines lw 1.5 title 'selective refinement'

  set output 'fronts.svg'
  set title title."\nvertex front and mesh size"
  set ylabel 'vertices / triangles'
  plot data skip 1 using 1:6 with lines lw 1.5 title 'triangles', \
       data skip 1 using 1:5 with lines lw 1.5 title 'front (active vertices)'

  set output 'operations.svg'
  set title title."\nmesh changes per frame"
  set ylabel 'operations'
  plot data skip 1 using 1:2 with lines lw 1.5 title 'vertex splits', \
       data skip 1 using 1:3 with lines dt 2 title 'edge collapses'
}
}
}
unset output
