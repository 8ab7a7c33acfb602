// gpu_probe [DEVICE]: prints what sdb::gpu::probe() finds (the device a run would use); exit
// status 0 when a device is available, 1 when not.
#include <cstdio>

#include "harness/gpu/device_info.h"

int main(int argc, char** argv) {
  const sdb::gpu::DeviceInfo info = sdb::gpu::probe(argc > 1 ? argv[1] : "");
  std::fputs(sdb::gpu::describe(info).c_str(), stdout);
  return info.available ? 0 : 1;
}
