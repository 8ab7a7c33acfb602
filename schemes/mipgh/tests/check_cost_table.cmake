# `subdivbench paper shiue2003-cost --out OUT` exits 0 and writes its table: the paper's claim and
# both of our counts (valgrind is installed by scripts/setup).
# -DSUBDIVBENCH=<executable> -DOUT=<folder>
set(ID shiue2003-cost)
set(ARGS)
set(EXPECT "| paper (simulated GPU) |" "| ours, the steps alone (`limit=0`) |" "| ours, with limit projection |")
include(${CMAKE_CURRENT_LIST_DIR}/../../../cmake/check_paper_table.cmake)
