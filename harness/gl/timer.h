// Timestamps around labelled passes of OpenGL work, read back as the sdb::GpuTimes every GPU row
// reports (upload, kernel, readback and each pass). Timestamp pairs (glQueryCounter), not
// GL_TIME_ELAPSED: Mesa's llvmpipe answers 0 for elapsed-time queries around compute dispatches
// and buffer transfers (measured), while its timestamps are the real clock.
//
//   timer.begin(PassKind::Upload, "upload"); ...; timer.end();
//   timer.begin(PassKind::Kernel, "eval stencils"); ...; timer.end();
//   GpuTimes t = timer.read();   // waits for the results
#pragma once

#include <string>
#include <vector>

#include "harness/core/gpu_times.h"
#include "harness/gl/context.h"

namespace sdb::gl {

enum class PassKind { Upload, Kernel, Readback };

class PassTimer {
 public:
  explicit PassTimer(const Context& ctx) : f_(&ctx.functions()) {}
  ~PassTimer();
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

  void clear();  // forget the passes recorded so far (their queries are reused)
  void begin(PassKind kind, std::string label);
  void end();
  // The passes since clear(); Upload passes sum to upload_ms, Kernel to kernel_ms, Readback to
  // readback_ms.
  GpuTimes read() const;

 private:
  struct Pass {
    std::string label;
    PassKind kind;
    GLuint begin_query, end_query;
  };
  const Functions* f_;
  std::vector<Pass> passes_;
  std::vector<GLuint> spare_;  // queries of cleared passes
  GLuint query();
};

}  // namespace sdb::gl
