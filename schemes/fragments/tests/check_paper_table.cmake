# `subdivbench paper shiue-loop-table1 --quick --out OUT` exits 0 and writes its Markdown table,
# with the poster's rows, ours, and the peer's rate beside ours.
# -DSUBDIVBENCH=<executable> -DOUT=<folder>
set(ID shiue-loop-table1)
set(ARGS --quick)
set(EXPECT "| 2 (poster) | 22.83 |" "| ours |" "osd-uniform-loop cpu M tri/s" "pmp/icosahedron_subdiv")
include(${CMAKE_CURRENT_LIST_DIR}/../../../cmake/check_paper_table.cmake)
