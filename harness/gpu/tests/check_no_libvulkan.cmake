# Fails when BINARY lists libvulkan among its DT_NEEDED libraries.
execute_process(COMMAND readelf -d ${BINARY} OUTPUT_VARIABLE dynamic RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "readelf -d ${BINARY} failed")
endif()
if(dynamic MATCHES "libvulkan")
  message(FATAL_ERROR "${BINARY} links libvulkan at load time; the loader must be opened at run time")
endif()
message(STATUS "${BINARY}: no libvulkan among its needed libraries")
