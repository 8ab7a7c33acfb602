# sdb_add_scheme: a scheme folder as one self-registering plug-in.
#
#   sdb_add_scheme(<family> SOURCES <file>...
#                  [SHADERS <file>...] [SHADER_INCLUDE_DIRS <dir>...]
#                  [LIBS <target>...] [COMPILE_OPTIONS <flag>...] [TEST_ONLY])
#
# Makes the static library sdb_scheme_<family> from the folder's sources (its scheme.cpp holds
# the SDB_REGISTER_* lines, harness/core/registry.h), embeds its shaders (sdb_add_shaders; the
# generated header sdb_scheme_<family>_shaders.h), and sdb_scheme_<family>_registered, which
# links it whole (--whole-archive) so that the registrations survive static linking. A scheme may
# use every harness module; nothing in the harness links or includes it. Unless TEST_ONLY, the
# library joins sdb_all_schemes, which the subdivbench executable links.
#
#   sdb_add_scheme_test(<name> <family> SOURCES <file>... [LIBS <target>...] [PROPERTIES ...])
#
# A gtest executable of the scheme's tests/ (sdb_add_test), linked to the scheme whole and to the
# conformance suite (harness/conformance), so that `SDB_CONFORMANCE_SUITE(...)` is one line.

define_property(GLOBAL PROPERTY SDB_SCHEME_LIBRARIES
  BRIEF_DOCS "scheme libraries linked into subdivbench"
  FULL_DOCS "appended to by sdb_add_scheme; read by schemes/CMakeLists.txt")

function(sdb_add_scheme family)
  cmake_parse_arguments(S "TEST_ONLY" "" "SOURCES;SHADERS;SHADER_INCLUDE_DIRS;LIBS;COMPILE_OPTIONS" ${ARGN})
  if(NOT S_SOURCES)
    message(FATAL_ERROR "sdb_add_scheme(${family}): SOURCES are required")
  endif()
  if(S_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "sdb_add_scheme(${family}): unknown arguments ${S_UNPARSED_ARGUMENTS}")
  endif()
  set(lib sdb_scheme_${family})
  add_library(${lib} STATIC ${S_SOURCES})
  target_link_libraries(${lib} PUBLIC sdb_bench ${S_LIBS} PRIVATE sdb_warnings)
  if(S_COMPILE_OPTIONS)
    target_compile_options(${lib} PRIVATE ${S_COMPILE_OPTIONS})
  endif()
  target_compile_definitions(${lib} PRIVATE SDB_SOURCE_DIR="${SDB_SOURCE_DIR}" SDB_BINARY_DIR="${CMAKE_BINARY_DIR}")
  if(S_SHADERS)
    sdb_add_shaders(TARGET ${lib} INCLUDE_DIRS ${S_SHADER_INCLUDE_DIRS} SHADERS ${S_SHADERS})
  endif()
  add_library(${lib}_registered INTERFACE)
  target_link_libraries(${lib}_registered INTERFACE "$<LINK_LIBRARY:WHOLE_ARCHIVE,${lib}>")
  if(NOT S_TEST_ONLY)
    set_property(GLOBAL APPEND PROPERTY SDB_SCHEME_LIBRARIES ${lib}_registered)
  endif()
endfunction()

function(sdb_add_scheme_test name family)
  cmake_parse_arguments(T "" "" "SOURCES;LIBS;PROPERTIES" ${ARGN})
  # The conformance suite's cases run as one ctest test (sdb_add_test's BATCHED) where a source
  # instantiates it.
  set(batched "")
  foreach(source ${T_SOURCES})
    file(READ ${source} text)
    if(text MATCHES "SDB_CONFORMANCE_SUITE")
      set(batched BATCHED "Conformance/*")
    endif()
  endforeach()
  sdb_add_test(${name} SOURCES ${T_SOURCES} LIBS sdb_scheme_${family}_registered sdb_conformance ${T_LIBS}
               PROPERTIES ${T_PROPERTIES} ${batched})
endfunction()
