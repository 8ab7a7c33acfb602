// The target that builds the tests' precompiled header (CMakeLists.txt, sdb_test_pch); no code.
