// The machine probes measured once and reused (machine.h): kept where $SUBDIVBENCH_MACHINE_PROBES
// names a folder, read back with probes_from naming the file, and measured anew where the device
// environment differs, the file describes another machine, or the variable is unset.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include <unistd.h>

#include "harness/bench/machine.h"

using namespace sdb;
namespace fs = std::filesystem;

namespace {

// Sets a variable for one scope and puts back what was there.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    value ? setenv(name, value, 1) : unsetenv(name);
  }
  ~ScopedEnv() { old_ ? setenv(name_, old_->c_str(), 1) : unsetenv(name_); }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

class MachineProbes : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("sdb-machine-probes-" + std::to_string(getpid()));
    fs::remove_all(folder_);
    env_.emplace(kMachineProbesVariable, folder_.c_str());
  }
  void TearDown() override { fs::remove_all(folder_); }

  // A block as a run measures it: this machine without its devices probed, bandwidths set.
  static MachineInfo measured() {
    MachineInfo m = describe_machine(false);
    m.write_bandwidth_gbs = 12.5, m.write_bandwidth_mt_gbs = 20.25;
    return m;
  }
  size_t files() const {
    size_t n = 0;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(folder_, ec)) n += e.is_regular_file();
    return n;
  }
  fs::path only_file() const { return fs::directory_iterator(folder_)->path(); }

  fs::path folder_;
  std::optional<ScopedEnv> env_;
};

TEST_F(MachineProbes, KeptOnceAndReadBackWithTheirOrigin) {
  EXPECT_FALSE(reused_machine_probes()) << "nothing kept yet";
  keep_machine_probes(measured());
  ASSERT_EQ(files(), 1u);
  const std::optional<MachineInfo> back = reused_machine_probes();
  ASSERT_TRUE(back);
  EXPECT_EQ(back->probes_from, only_file().string());
  EXPECT_DOUBLE_EQ(back->write_bandwidth_gbs, 12.5);
  EXPECT_DOUBLE_EQ(back->write_bandwidth_mt_gbs, 20.25);
  EXPECT_EQ(describe_machine_or_reuse().probes_from, only_file().string());
  // A reused block is not written again (its probes were not measured here).
  keep_machine_probes(*back);
  EXPECT_EQ(files(), 1u);
}

TEST_F(MachineProbes, AnotherDeviceEnvironmentMeasuresAnew) {
  keep_machine_probes(measured());
  ASSERT_TRUE(reused_machine_probes());
  {
    const ScopedEnv hidden("VK_ICD_FILENAMES", "/nonexistent");  // as the no-device tests set it
    EXPECT_FALSE(reused_machine_probes());
    EXPECT_TRUE(describe_machine_or_reuse().probes_from.empty());
  }
  EXPECT_TRUE(reused_machine_probes());
}

TEST_F(MachineProbes, AFileDescribingAnotherMachineIsNotUsed) {
  keep_machine_probes(measured());
  const fs::path file = only_file();
  MachineInfo other = measured();
  other.cpu_model = "another CPU";
  fs::remove(file);
  keep_machine_probes(other);
  ASSERT_EQ(only_file(), file) << "the same boot, build and environment name the same file";
  EXPECT_FALSE(reused_machine_probes());
  // Nor a file cut short.
  std::ofstream(file, std::ios::trunc) << "{\"schema\":";
  EXPECT_FALSE(reused_machine_probes());
}

TEST_F(MachineProbes, WithoutTheVariableNothingIsKeptOrReused) {
  keep_machine_probes(measured());
  ASSERT_TRUE(reused_machine_probes());
  const ScopedEnv unset(kMachineProbesVariable, nullptr);
  EXPECT_FALSE(reused_machine_probes());
  fs::remove_all(folder_);
  keep_machine_probes(measured());
  EXPECT_FALSE(fs::exists(folder_));
}

}  // namespace
