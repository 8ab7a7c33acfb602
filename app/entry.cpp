// subdivbench: every registered scheme (sdb_all_schemes) behind the verbs of app/ (the composition root).
#include "app/main.h"

int main(int argc, char** argv) { return sdb::app::main(argc, argv); }
