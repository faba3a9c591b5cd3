# The required flag of every section every lodbake writer produces, read
# back with lodbake-inspect --json and compared with the table of
# docs/format.md section 4 (which this script parses, so the specification
# and the writers cannot drift apart). Also checks that every tag of the
# table is written by some tool. Run with cmake -P:
#   -DTOOLS=<build>/tools -DSRC=<source dir> -DOUT=<scratch dir>
cmake_minimum_required(VERSION 3.19)  # string(JSON)
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
set(mesh ${SRC}/tests/golden/inputs/icosphere42.off)

# tag -> yes/no from the specification's table.
file(STRINGS ${SRC}/docs/format.md rows REGEX "^\\| `[A-Z][A-Z][A-Z][A-Z]` \\| (yes|no) \\|")
set(spec_tags "")
foreach(row IN LISTS rows)
  string(REGEX MATCH "^\\| `([A-Z]+)` \\| (yes|no) \\|" _ "${row}")
  set(spec_${CMAKE_MATCH_1} ${CMAKE_MATCH_2})
  list(APPEND spec_tags ${CMAKE_MATCH_1})
endforeach()
list(LENGTH spec_tags spec_count)
if(spec_count LESS 10)
  message(FATAL_ERROR "docs/format.md section 4: found ${spec_count} rows of the flag table")
endif()

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " shown "${ARGN}")
    message(FATAL_ERROR "${shown}: exit code ${rc}: ${err}")
  endif()
endfunction()

# Every writer, with the containers it writes.
run(${TOOLS}/lodbake-pack -q ${mesh} -o ${OUT}/pack.lbk)
run(${TOOLS}/lodbake-simplify -q ${mesh} --ratio 0.5 --pm ${OUT}/pm.lbk)
run(${TOOLS}/lodbake-hierarchy -q ${mesh} -o ${OUT}/hierarchy.lbk)
run(${TOOLS}/lodbake-fan -q ${mesh} -o ${OUT}/fan.lbk)
run(${TOOLS}/lodbake-strips -q ${OUT}/pm.lbk -o ${OUT}/sets.lbk)
run(${TOOLS}/lodbake-strips -q ${mesh} --strips-only -o ${OUT}/strips.lbk)
# pack merging containers of one input, and repacking one whose flags an
# earlier writer set otherwise (inputs/grid5_pm.lbk flags VSPL required).
run(${TOOLS}/lodbake-pack -q ${OUT}/pack.lbk ${OUT}/fan.lbk ${OUT}/strips.lbk -o ${OUT}/merged.lbk)
run(${TOOLS}/lodbake-pack -q ${OUT}/hierarchy.lbk --raw -o ${OUT}/hierarchy_raw.lbk)
run(${TOOLS}/lodbake-pack -q ${SRC}/tests/golden/inputs/grid5_pm.lbk -o ${OUT}/grid5.lbk)

set(failures "")
set(seen "")
foreach(name pack pm hierarchy fan sets strips merged hierarchy_raw grid5)
  execute_process(COMMAND ${TOOLS}/lodbake-inspect --json ${OUT}/${name}.lbk
                  RESULT_VARIABLE rc OUTPUT_VARIABLE json ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "lodbake-inspect ${name}.lbk: exit code ${rc}: ${err}")
  endif()
  string(JSON count LENGTH "${json}" container sections)
  math(EXPR last "${count} - 1")
  set(listed "")
  foreach(i RANGE ${last})
    string(JSON tag GET "${json}" container sections ${i} tag)
    string(JSON required GET "${json}" container sections ${i} required)
    list(APPEND listed ${tag})
    list(APPEND seen ${tag})
    if(NOT DEFINED spec_${tag})
      string(APPEND failures "${name}.lbk: section ${tag} is not in the table\n")
    elseif((spec_${tag} STREQUAL "yes") AND NOT required)
      string(APPEND failures "${name}.lbk: ${tag} is optional, the table says required\n")
    elseif((spec_${tag} STREQUAL "no") AND required)
      string(APPEND failures "${name}.lbk: ${tag} is required, the table says optional\n")
    endif()
  endforeach()
  message(STATUS "${name}.lbk: ${listed}")
endforeach()
foreach(tag IN LISTS spec_tags)
  if(NOT tag IN_LIST seen)
    string(APPEND failures "no tool output holds ${tag}\n")
  endif()
endforeach()
if(NOT failures STREQUAL "")
  message(FATAL_ERROR "section flags differ from docs/format.md section 4:\n${failures}")
endif()
