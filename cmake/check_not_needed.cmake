# Fails when BINARY lists a library matching PATTERN among its DT_NEEDED libraries: such a library
# must be opened at run time, for the reason WHY.
# -DBINARY=<executable> -DPATTERN=<regex> -DWHY=<text>
execute_process(COMMAND readelf -d ${BINARY} OUTPUT_VARIABLE dynamic RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "readelf -d ${BINARY} failed")
endif()
if(dynamic MATCHES "${PATTERN}")
  message(FATAL_ERROR "${BINARY} loads ${CMAKE_MATCH_0} at start; it must be opened at run time (${WHY})")
endif()
message(STATUS "${BINARY}: nothing matching ${PATTERN} among its needed libraries")
