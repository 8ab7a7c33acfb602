# `subdivbench paper shiue2003-cost --out OUT` exits 0 and writes its table: the paper's claim and
# both of our counts (valgrind is installed by scripts/setup).
# -DSUBDIVBENCH=<executable> -DOUT=<folder>
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${SUBDIVBENCH} paper shiue2003-cost --out ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "subdivbench paper shiue2003-cost exited with ${rc}")
endif()
set(table ${OUT}/shiue2003-cost.md)
if(NOT EXISTS ${table})
  message(FATAL_ERROR "no ${table}")
endif()
file(READ ${table} md)
foreach(expected "| paper (simulated GPU) |" "| ours, the steps alone (`limit=0`) |" "| ours, with limit projection |")
  string(FIND "${md}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${table} lacks '${expected}'")
  endif()
endforeach()
