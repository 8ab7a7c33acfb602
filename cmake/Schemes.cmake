# sdb_add_scheme: a scheme folder as one self-registering plug-in.
#
#   sdb_add_scheme(<family> SOURCES <file>... [EXPERIMENTS <file>...]
#                  [SHADERS <file>...] [SHADER_INCLUDE_DIRS <dir>...]
#                  [LIBS <target>...] [COMPILE_OPTIONS <flag>...] [TEST_ONLY])
#
# Makes the static library sdb_scheme_<family> from the folder's sources (its scheme.cpp holds
# the SDB_REGISTER_SCHEMES line, harness/core/registry.h), embeds its shaders (sdb_add_shaders; the
# generated header sdb_scheme_<family>_shaders.h), and sdb_scheme_<family>_registered, which
# links it whole (--whole-archive) so that the registrations survive static linking. The algorithm
# links the harness's contract, meshes and Vulkan backend (sdb_core, sdb_mesh, sdb_gpu) and what
# LIBS adds (sdb_reference, sdb_validate, sdb_gl, sdb_refined, third-party libraries); never the
# measurement (sdb_bench) nor Google Benchmark: cmake/module_graph.txt and the test
# scheme_libraries_link_no_benchmark hold it to that.
#
# EXPERIMENTS are the folder's paper tables (paper/, with their SDB_REGISTER_PAPER_TABLES line):
# the library sdb_scheme_<family>_experiments on top of the algorithm and the measurement, linked
# whole into subdivbench beside it. Nothing in the harness links or includes either. Unless
# TEST_ONLY, both join sdb_all_schemes, which the subdivbench executable links.
#
#   sdb_add_scheme_test(<name> <family> SOURCES <file>... [LIBS <target>...] [PROPERTIES ...])
#
# A gtest executable of the scheme's tests/ (sdb_add_test), linked to the scheme whole and to the
# conformance suite (harness/conformance), so that `SDB_CONFORMANCE_SUITE(...)` is one line.
#
#   sdb_add_scheme_dirs(<dir>...)
#
# Each folder a plug-in as above, wherever it lives (SUBDIVBENCH_SCHEME_DIRS: schemes from
# outside the tree, schemes/README.md).

define_property(GLOBAL PROPERTY SDB_SCHEME_LIBRARIES
  BRIEF_DOCS "scheme libraries linked into subdivbench"
  FULL_DOCS "appended to by sdb_add_scheme; read by schemes/CMakeLists.txt")

function(sdb_add_scheme family)
  cmake_parse_arguments(S "TEST_ONLY" "" "SOURCES;EXPERIMENTS;SHADERS;SHADER_INCLUDE_DIRS;LIBS;COMPILE_OPTIONS" ${ARGN})
  if(NOT S_SOURCES)
    message(FATAL_ERROR "sdb_add_scheme(${family}): SOURCES are required")
  endif()
  if(S_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "sdb_add_scheme(${family}): unknown arguments ${S_UNPARSED_ARGUMENTS}")
  endif()
  set(lib sdb_scheme_${family})
  add_library(${lib} STATIC ${S_SOURCES})
  target_link_libraries(${lib} PUBLIC sdb_core sdb_mesh sdb_gpu ${S_LIBS} PRIVATE sdb_warnings)
  if(S_COMPILE_OPTIONS)
    target_compile_options(${lib} PRIVATE ${S_COMPILE_OPTIONS})
  endif()
  target_compile_definitions(${lib} PRIVATE SDB_SOURCE_DIR="${SDB_SOURCE_DIR}" SDB_BINARY_DIR="${CMAKE_BINARY_DIR}")
  if(S_SHADERS)
    sdb_add_shaders(TARGET ${lib} INCLUDE_DIRS ${S_SHADER_INCLUDE_DIRS} SHADERS ${S_SHADERS})
  endif()
  add_library(${lib}_registered INTERFACE)
  target_link_libraries(${lib}_registered INTERFACE "$<LINK_LIBRARY:WHOLE_ARCHIVE,${lib}>")
  set_property(GLOBAL APPEND PROPERTY SDB_SCHEME_ALGORITHMS ${lib})
  if(NOT S_TEST_ONLY)
    set_property(GLOBAL APPEND PROPERTY SDB_SCHEME_LIBRARIES ${lib}_registered)
  endif()
  if(S_EXPERIMENTS)
    set(experiments ${lib}_experiments)
    add_library(${experiments} STATIC ${S_EXPERIMENTS})
    # The algorithm whole, as everywhere else it is linked: one library linked two ways is refused.
    target_link_libraries(${experiments} PUBLIC ${lib}_registered sdb_bench sdb_gate sdb_datasets PRIVATE sdb_warnings)
    if(S_COMPILE_OPTIONS)
      target_compile_options(${experiments} PRIVATE ${S_COMPILE_OPTIONS})
    endif()
    target_compile_definitions(${experiments} PRIVATE SDB_SOURCE_DIR="${SDB_SOURCE_DIR}" SDB_BINARY_DIR="${CMAKE_BINARY_DIR}")
    add_library(${experiments}_registered INTERFACE)
    target_link_libraries(${experiments}_registered INTERFACE "$<LINK_LIBRARY:WHOLE_ARCHIVE,${experiments}>")
    if(NOT S_TEST_ONLY)
      set_property(GLOBAL APPEND PROPERTY SDB_SCHEME_LIBRARIES ${experiments}_registered)
    endif()
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

function(sdb_add_scheme_dirs)
  set(index 0)
  foreach(dir ${ARGN})
    if(NOT IS_ABSOLUTE ${dir})
      message(FATAL_ERROR "SUBDIVBENCH_SCHEME_DIRS: ${dir} is not an absolute path")
    endif()
    if(NOT EXISTS ${dir}/CMakeLists.txt)
      message(FATAL_ERROR "SUBDIVBENCH_SCHEME_DIRS: ${dir}/CMakeLists.txt does not exist (a scheme folder holds one "
                          "calling sdb_add_scheme, as schemes/<scheme>/ does)")
    endif()
    get_filename_component(folder ${dir} NAME)
    math(EXPR index "${index} + 1")
    # A folder outside the source tree needs a build folder of its own.
    add_subdirectory(${dir} ${CMAKE_BINARY_DIR}/scheme-dirs/${index}-${folder})
  endforeach()
endfunction()

# sdb_write_scheme_links(<file>): each scheme algorithm library (sdb_add_scheme, in-tree or from
# SUBDIVBENCH_SCHEME_DIRS) and every target it links, transitively, one library a line
# ("sdb_scheme_cpatch: sdb_core sdb_mesh ..."): what tests/layering/check_scheme_links.cmake
# reads to hold the algorithms to cmake/module_graph.txt at link level too. Called once every
# target exists (the end of the top CMakeLists.txt).
function(sdb_link_closure target out)
  set(seen "")
  set(queue ${target})
  while(queue)
    list(POP_FRONT queue item)
    if(item IN_LIST seen OR NOT TARGET ${item})
      continue()
    endif()
    list(APPEND seen ${item})
    set(links "")
    foreach(property LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
      get_target_property(value ${item} ${property})
      if(value)
        list(APPEND links ${value})
      endif()
    endforeach()
    foreach(link ${links})
      # $<LINK_ONLY:x> and $<LINK_LIBRARY:FEATURE,x> name x; other expressions (configurations) no target.
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" link "${link}")
      string(REGEX REPLACE "^\\$<LINK_LIBRARY:[A-Z_]+,(.*)>$" "\\1" link "${link}")
      if(NOT link MATCHES "^\\$<" AND NOT link IN_LIST seen)
        list(APPEND queue ${link})
      endif()
    endforeach()
  endwhile()
  list(REMOVE_ITEM seen ${target})
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

function(sdb_write_scheme_links file)
  get_property(algorithms GLOBAL PROPERTY SDB_SCHEME_ALGORITHMS)
  set(text "")
  foreach(lib ${algorithms})
    sdb_link_closure(${lib} closure)
    list(JOIN closure " " closure)
    string(APPEND text "${lib}: ${closure}\n")
  endforeach()
  file(WRITE ${file} "${text}")
endfunction()
