# `subdivbench paper shiue2003-cost --out OUT` exits 0 and writes its table: the paper's claim and
# both of our counts (valgrind is installed by scripts/setup).
# -DSUBDIVBENCH=<executable> -DOUT=<folder>
set(ID shiue2003-cost)
# Where valgrind cannot run the executable on this machine at all (callgrind.h, valgrind_unusable),
# the table says so: the test is skipped (SKIP_REGULAR_EXPRESSION), never passed.
set(SKIP_IF "valgrind cannot run")
set(ARGS)
set(EXPECT "| paper (simulated GPU) |" "| ours, the steps alone (`limit=0`) |" "| ours, with limit projection |")
include(${CMAKE_CURRENT_LIST_DIR}/../../../cmake/check_paper_table.cmake)
