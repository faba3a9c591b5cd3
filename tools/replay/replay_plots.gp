# Paper-style charts of one lodbake-replay run (lodbake-replay --plot DIR).
# lodbake-replay writes this script into DIR with the variables below set
# in front of it, the per-frame rows (the --csv columns) as frames.csv, and
# runs gnuplot in DIR. Edit and re-run it there with `gnuplot replay.gp`.
#   mode   'vhier' or 'dag'
#   lanes  the dag traversals replayed, e.g. 'priority linear constant'
#   title  shown above every chart

set terminal svg size 900,520 dynamic enhanced font 'sans,12' background rgb 'white'
set datafile separator ','
set grid
set key outside right top
set xlabel 'frame'
data = 'frames.csv'
lane_title(name) = name eq 'priority' ? 'priority-oriented' : (name eq 'constant' ? 'constant-time' : name)
# Value of column c in rows of lane `name`; no point elsewhere.
in_lane(name, c) = strcol(2) eq name ? column(c) : NaN

if (mode eq 'dag') {
  # dag columns: frame,traversal,splits,collapses,visited,budget_mode,fs,fc,triangles,traversal_ms,accuracy

  # The DAG paper's Figure 6.
  set output 'traversal_time.svg'
  set title title."\ntraversal time per frame"
  set ylabel 'traversal time (ms)'
  plot for [i=1:words(lanes)] data skip 1 using 1:(in_lane(word(lanes, i), 10)) \
    with lines lw 1.5 title lane_title(word(lanes, i))

  # Figure 7: share of the priority-oriented traversal's triangles.
  if (words(lanes) > 1 || word(lanes, 1) ne 'priority') {
    set output 'accuracy.svg'
    set title title."\naccuracy against the priority-oriented traversal"
    set ylabel 'accuracy (%)'
    set yrange [0:100]
    plot for [i=1:words(lanes)] data skip 1 \
      using 1:(word(lanes, i) ne 'priority' ? 100 * in_lane(word(lanes, i), 11) : NaN) \
      with lines lw 1.5 title lane_title(word(lanes, i))
    unset yrange
  }

  # Figure 9: the fronts against the mesh, for the first traversal.
  first = word(lanes, 1)
  set output 'fronts.svg'
  set title title."\nfront sizes and mesh size (".lane_title(first)." traversal)"
  set ylabel 'nodes / triangles'
  plot data skip 1 using 1:(in_lane(first, 9)) with lines lw 1.5 title 'triangles', \
       data skip 1 using 1:(in_lane(first, 7) + in_lane(first, 8)) with lines lw 1.5 title '|Fs| + |Fc|', \
       data skip 1 using 1:(in_lane(first, 7)) with lines title '|Fs|', \
       data skip 1 using 1:(in_lane(first, 8)) with lines title '|Fc|'

  set output 'operations.svg'
  set title title."\nmesh changes per frame"
  set ylabel 'operations'
  plot for [i=1:words(lanes)] data skip 1 using 1:(in_lane(word(lanes, i), 3)) \
         with lines lw 1.5 title lane_title(word(lanes, i)).' splits', \
       for [i=1:words(lanes)] data skip 1 using 1:(in_lane(word(lanes, i), 4)) \
         with lines dt 2 title lane_title(word(lanes, i)).' collapses'
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
unset output
