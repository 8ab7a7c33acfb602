# shiue2003-fig22's displacement image refused in one line naming it, exit 2, and the earlier
# results in the same folder left intact: a missing file, a file OpenImageIO cannot read, and an
# image whose header announces 99999 x 99999 pixels (refused before anything is allocated).
# -DSUBDIVBENCH=<executable> -DOUT=<folder> -DREADME=<a text file>
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${SUBDIVBENCH} paper shiue2003-fig22 --quick --out ${OUT} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the first, good run exited with ${rc}")
endif()
file(READ ${OUT}/shiue2003-fig22.md before)
file(WRITE ${OUT}/lying.pgm "P5\n99999 99999\n255\n")
set(cases "${OUT}/no-such-image.png|no such displacement image"
          "${README}|unreadable displacement image"
          "${OUT}/lying.pgm|past 2^30 values")
foreach(case IN LISTS cases)
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 image)
  list(GET parts 1 expected)
  execute_process(COMMAND ${SUBDIVBENCH} paper shiue2003-fig22 --quick --texture ${image} --out ${OUT}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "${image}: exit ${rc}, not 2")
  endif()
  string(FIND "${err}" "${image}: " named)
  string(FIND "${err}" "${expected}" said)
  string(REGEX MATCHALL "\n" lines "${err}")
  list(LENGTH lines count)
  if(named EQUAL -1 OR said EQUAL -1 OR count GREATER 1)
    message(FATAL_ERROR "${image}: not one line naming it and saying '${expected}': ${err}")
  endif()
  file(READ ${OUT}/shiue2003-fig22.md after)
  if(NOT after STREQUAL before)
    message(FATAL_ERROR "${image}: the earlier table was changed")
  endif()
endforeach()
