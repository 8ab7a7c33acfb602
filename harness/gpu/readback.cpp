#include "harness/gpu/readback.h"

namespace sdb::gpu {

OutputReadback::OutputReadback(Context& ctx, const Buffer& positions, const Buffer& normals, uint64_t bytes)
    : ctx_(&ctx),
      positions_staging_(Buffer::readback(ctx, bytes, "positions (readback)")),
      normals_staging_(Buffer::readback(ctx, bytes, "normals (readback)")) {
  timer_.emplace(ctx, 1);
  recording_ = ctx.record([&](Commands& cmd) {
    timer_->reset(cmd);
    timer_->begin(cmd, PassKind::Readback, "readback");
    cmd.download(positions, positions_staging_);
    cmd.download(normals, normals_staging_);
    timer_->end(cmd);
  });
}

void OutputReadback::read_into(Tessellation& out) {
  if (!stale_) return;
  ctx_->submit(*recording_);
  read_ = true;
  positions_staging_.read(out.positions.data(), out.positions.size() * sizeof(Point3));
  normals_staging_.read(out.normals.data(), out.normals.size() * sizeof(Point3));
  stale_ = false;
}

void OutputReadback::append_passes(std::vector<PassTimestamps>& passes) const {
  if (!read_) return;
  if (auto readback = timer_->read_passes()) passes.insert(passes.end(), readback->begin(), readback->end());
}

}  // namespace sdb::gpu
