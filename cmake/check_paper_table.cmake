# Included by a scheme's tests/check_*.cmake (run with cmake -P): `subdivbench paper ID ARGS --out
# OUT` exits 0 and writes OUT/ID.md holding every string of EXPECT.
# Set before including: ID, ARGS (a list, may be empty), EXPECT (a list), optionally SKIP_IF (a
# string that, found in the table, says the machine cannot measure it: the script prints
# "SKIPPED: ..." for the test's SKIP_REGULAR_EXPRESSION and checks nothing); -DSUBDIVBENCH=<executable>
# -DOUT=<folder> on the command line.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${SUBDIVBENCH} paper ${ID} ${ARGS} --out ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "subdivbench paper ${ID} ${ARGS} exited with ${rc}")
endif()
set(table ${OUT}/${ID}.md)
if(NOT EXISTS ${table})
  message(FATAL_ERROR "no ${table}")
endif()
file(READ ${table} md)
if(DEFINED SKIP_IF)
  string(FIND "${md}" "${SKIP_IF}" skip_at)
  if(NOT skip_at EQUAL -1)
    message("SKIPPED: ${table} says '${SKIP_IF}'")
    return()
  endif()
endif()
foreach(expected IN LISTS EXPECT)
  string(FIND "${md}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${table} lacks '${expected}'")
  endif()
endforeach()
