cmake_minimum_required(VERSION 3.25)
# Fails when a file under harness/, datasets/ or reports/ includes a header that lives under
# schemes/ (or tests/schemes/), by path or by bare name: the harness learns a scheme's policy from
# its SchemeInfo, through the registry, never from its headers.
#   cmake -DSOURCE_DIR=<root> -P check_layering.cmake
file(GLOB_RECURSE scheme_headers RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/schemes/*.h ${SOURCE_DIR}/tests/schemes/*.h)
file(GLOB_RECURSE harness_headers RELATIVE ${SOURCE_DIR}
     ${SOURCE_DIR}/harness/*.h ${SOURCE_DIR}/datasets/*.h ${SOURCE_DIR}/reports/*.h)
set(harness_names "")
foreach(h ${harness_headers})
  get_filename_component(n ${h} NAME)
  list(APPEND harness_names ${n})
endforeach()
set(scheme_only_names "")
foreach(h ${scheme_headers})
  get_filename_component(n ${h} NAME)
  if(NOT n IN_LIST harness_names)
    list(APPEND scheme_only_names ${n})
  endif()
endforeach()

file(GLOB_RECURSE sources RELATIVE ${SOURCE_DIR}
     ${SOURCE_DIR}/harness/*.h ${SOURCE_DIR}/harness/*.cpp ${SOURCE_DIR}/datasets/*.h ${SOURCE_DIR}/datasets/*.cpp
     ${SOURCE_DIR}/reports/*.h ${SOURCE_DIR}/reports/*.cpp)
set(bad "")
foreach(f ${sources})
  file(STRINGS ${SOURCE_DIR}/${f} includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(line ${includes})
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\".*$" "\\1" inc "${line}")
    # A bare name ("cpatch.h") would reach a scheme through an include path, a path by itself.
    if(inc MATCHES "^(tests/)?schemes/" OR (NOT inc MATCHES "/" AND inc IN_LIST scheme_only_names))
      list(APPEND bad "${f}: #include \"${inc}\"")
    endif()
  endforeach()
endforeach()
if(bad)
  list(JOIN bad "\n  " text)
  message(FATAL_ERROR "harness/, datasets/ or reports/ include scheme headers:\n  ${text}")
endif()
list(LENGTH sources n)
message(STATUS "layering: ${n} harness, datasets and reports files include no scheme header")
