# `subdivbench paper losasso2003-table2 --quick --out OUT` exits 0 and writes its Markdown table.
# -DSUBDIVBENCH=<executable> -DOUT=<folder>
set(ID losasso2003-table2)
set(ARGS --quick)
set(EXPECT "paper GPU R9700 time (ms)" "ours cpu `geometry-image` time (ms)" "osd-uniform" "| k = 1 | k = 2 |")
include(${CMAKE_CURRENT_LIST_DIR}/../../../cmake/check_paper_table.cmake)
