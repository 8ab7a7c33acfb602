// The subdivbench command line as a function, so that an executable with test-only schemes
// (tests/CMakeLists.txt) runs the same verbs.
#pragma once

namespace sdb::app {

int main(int argc, char** argv);

}  // namespace sdb::app
