# Fails when BINARY lists OpenImageIO among its DT_NEEDED libraries (image_io.h says why).
execute_process(COMMAND readelf -d ${BINARY} OUTPUT_VARIABLE dynamic RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "readelf -d ${BINARY} failed")
endif()
if(dynamic MATCHES "OpenImageIO|libhwy|libjxl")
  message(FATAL_ERROR "${BINARY} loads OpenImageIO at start; the image module must be opened at run time")
endif()
message(STATUS "${BINARY}: no OpenImageIO among its needed libraries")
