#include "harness/gl/timer.h"

#include <stdexcept>

namespace sdb::gl {

PassTimer::~PassTimer() {
  clear();
  if (!spare_.empty()) f_->DeleteQueries(static_cast<GLsizei>(spare_.size()), spare_.data());
}

GLuint PassTimer::query() {
  if (spare_.empty()) {
    GLuint q = 0;
    f_->GenQueries(1, &q);
    return q;
  }
  const GLuint q = spare_.back();
  spare_.pop_back();
  return q;
}

void PassTimer::clear() {
  for (const Pass& p : passes_) spare_.insert(spare_.end(), {p.begin_query, p.end_query});
  passes_.clear();
}

void PassTimer::begin(PassKind kind, std::string label) {
  if (!passes_.empty() && passes_.back().end_query == 0) throw std::logic_error("PassTimer: a pass is open");
  passes_.push_back({std::move(label), kind, query(), 0});
  f_->QueryCounter(passes_.back().begin_query, GL_TIMESTAMP);
}

void PassTimer::end() {
  if (passes_.empty() || passes_.back().end_query != 0) throw std::logic_error("PassTimer: no pass is open");
  passes_.back().end_query = query();
  f_->QueryCounter(passes_.back().end_query, GL_TIMESTAMP);
}

GpuTimes PassTimer::read() const {
  GpuTimes t;
  for (const Pass& p : passes_) {
    GLuint64 begin = 0, end = 0;
    f_->GetQueryObjectui64v(p.begin_query, GL_QUERY_RESULT, &begin);
    f_->GetQueryObjectui64v(p.end_query, GL_QUERY_RESULT, &end);
    const double ms = end > begin ? double(end - begin) * 1e-6 : 0.0;
    t.passes.push_back({p.label, ms});
    (p.kind == PassKind::Upload ? t.upload_ms : p.kind == PassKind::Kernel ? t.kernel_ms : t.readback_ms) += ms;
  }
  return t;
}

}  // namespace sdb::gl
