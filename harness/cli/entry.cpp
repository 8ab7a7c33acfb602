// subdivbench: every registered scheme (sdb_all_schemes) behind the verbs of harness/cli.
#include "harness/cli/main.h"

int main(int argc, char** argv) { return sdb::cli::main(argc, argv); }
