# Runs a command that writes OUTPUT and compares OUTPUT byte for byte with
# the committed GOLDEN file. With LODBAKE_UPDATE_GOLDEN=1 in the environment
# the golden file is rewritten instead (review the diff before committing).
#   -DCASE_CMD=a^^b^^c -DOUTPUT=... -DGOLDEN=...
string(REPLACE "^^" ";" CASE_CMD "${CASE_CMD}")
get_filename_component(out_dir "${OUTPUT}" DIRECTORY)
file(MAKE_DIRECTORY "${out_dir}")
file(REMOVE "${OUTPUT}")
execute_process(COMMAND ${CASE_CMD} RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "command failed (${rc}): ${err}")
endif()
if("$ENV{LODBAKE_UPDATE_GOLDEN}" STREQUAL "1")
  file(COPY_FILE "${OUTPUT}" "${GOLDEN}")
  message(STATUS "updated ${GOLDEN}")
  return()
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${OUTPUT}" "${GOLDEN}"
                RESULT_VARIABLE differs)
if(NOT differs EQUAL 0)
  message(FATAL_ERROR "${OUTPUT} differs from ${GOLDEN}: the output format or the "
                      "algorithm changed. If that is intended, bump the format version "
                      "where needed and regenerate with LODBAKE_UPDATE_GOLDEN=1.")
endif()
