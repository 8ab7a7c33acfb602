# `subdivbench paper shiue-loop-table1 --quick --out OUT` exits 0 and writes its Markdown table,
# with the poster's rows, ours, and the peer's rate beside ours.
# -DSUBDIVBENCH=<executable> -DOUT=<folder>
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${SUBDIVBENCH} paper shiue-loop-table1 --quick --out ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "subdivbench paper shiue-loop-table1 --quick exited with ${rc}")
endif()
set(table ${OUT}/shiue-loop-table1.md)
if(NOT EXISTS ${table})
  message(FATAL_ERROR "no ${table}")
endif()
file(READ ${table} md)
foreach(expected "| 2 (poster) | 22.83 |" "| ours |" "osd-uniform-loop cpu M tri/s" "pmp/icosahedron_subdiv")
  string(FIND "${md}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${table} lacks '${expected}'")
  endif()
endforeach()
