// osd-glcompute, osd-glcompute-loop: osd-stencil's limit stencil tables evaluated by OpenSubdiv's
// Osd::GLComputeEvaluator in the harness's headless OpenGL context (harness/gl, EGL), on the
// `opengl` backend: the one GPU peer these methods have (OpenSubdiv has no Vulkan evaluator).
// Upload (the control points), kernel (EvalStencils: positions and both tangents) and readback
// are timed by GL timestamps; normals are crossed from the read-back tangents on the CPU, as
// OpenSubdiv has no normal kernel (README.md).
#include <dlfcn.h>
#include <opensubdiv/osd/glComputeEvaluator.h>
#include <opensubdiv/osd/glVertexBuffer.h>

#include "harness/core/errors.h"
#include "harness/gl/context.h"
#include "harness/gl/timer.h"
#include "schemes/peers/limit_stencils.h"
#include "schemes/peers/peers.h"

// Exported by libosdGPU, its header (glLoader.h) not installed; outside the versioned namespace.
namespace OpenSubdiv::internal::GLLoader {
bool libraryInitializeGL();
}

namespace sdb {
namespace {

namespace Osd = OpenSubdiv::Osd;

// OpenSubdiv's GL loader: it opens libGL.so.1 and reads the current context's version once per
// process, so it runs after the harness's context is current. Its GLStencilTableSSBO does not
// call it and crashes when it comes first (measured), hence this before any OpenSubdiv GL object.
std::optional<std::string> initialise_opensubdiv_gl() {
  static const std::optional<std::string> failure = []() -> std::optional<std::string> {
    if (!dlopen("libGL.so.1", RTLD_LAZY | RTLD_LOCAL))
      return std::string("OpenSubdiv's GL loader needs libGL.so.1 (Debian: libgl1), which cannot be opened");
    if (!OpenSubdiv::internal::GLLoader::libraryInitializeGL()) return std::string("OpenSubdiv's GL loader failed");
    return std::nullopt;
  }();
  return failure;
}

std::optional<std::string> opengl_unavailable() {
  const gl::DeviceInfo info = gl::probe();
  if (!info.available) return "no OpenGL context: " + info.reason;
  return initialise_opensubdiv_gl();
}

class OsdGlComputeEvaluation final : public Evaluation {
 public:
  OsdGlComputeEvaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth)
      : ctx_(gl::shared_context()), control_(mesh), timer_(*ctx_) {
    PreparedStencils prepared = limit_stencils(mesh, rule, depth);
    stencils_ = std::move(prepared.stencils);
    out_ = std::move(prepared.topology);
    const int n = stencils_->table->GetNumStencils();  // the vertices with a limit patch
    const size_t vertices = out_.coords.size();
    out_.positions.resize(vertices);
    out_.normals.resize(vertices);
    du_.resize(3 * vertices);
    dv_.resize(3 * vertices);
    for (auto* v : {&dense_p_, &dense_du_, &dense_dv_}) v->resize(3 * size_t(n));
    source_.reset(Osd::GLVertexBuffer::Create(3, stencils_->control_points));
    for (auto* b : {&position_, &tangent_u_, &tangent_v_}) b->reset(Osd::GLVertexBuffer::Create(3, n));
    table_.reset(Osd::GLStencilTableSSBO::Create(stencils_->table.get()));
    evaluator_.reset(Osd::GLComputeEvaluator::Create(kDesc, kDesc, kDesc, kDesc));
    if (!evaluator_) throw std::runtime_error("Osd::GLComputeEvaluator::Create failed (its compute shader did not build)");
    ctx_->check("preparing the GL compute evaluator");
  }

  void execute() override {
    timer_.clear();
    timer_.begin(gl::PassKind::Upload, "upload control points");
    source_->UpdateData(control_.positions[0].data(), 0, stencils_->control_points);
    timer_.end();
    timer_.begin(gl::PassKind::Kernel, "GLComputeEvaluator::EvalStencils");
    const bool ok = Osd::GLComputeEvaluator::EvalStencils(source_.get(), kDesc, position_.get(), kDesc, tangent_u_.get(),
                                                          kDesc, tangent_v_.get(), kDesc, table_.get(), evaluator_.get());
    timer_.end();
    if (!ok) throw std::runtime_error("Osd::GLComputeEvaluator::EvalStencils failed");
    times_ = timer_.read();  // waits for the device
    stale_ = true;
  }

  const Tessellation& result() override {
    if (!stale_) return out_;
    const gl::Functions& f = ctx_->functions();
    f.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    timer_.clear();
    timer_.begin(gl::PassKind::Readback, "readback");
    read(*position_, dense_p_.data());
    read(*tangent_u_, dense_du_.data());
    read(*tangent_v_, dense_dv_.data());
    timer_.end();
    const GpuTimes readback = timer_.read();
    times_.readback_ms = readback.readback_ms;
    times_.passes.insert(times_.passes.end(), readback.passes.begin(), readback.passes.end());
    ctx_->check("reading back the GL compute evaluator's output");
    scatter_limit(*stencils_, dense_p_.data(), out_.positions[0].data());
    scatter_limit(*stencils_, dense_du_.data(), du_.data());
    scatter_limit(*stencils_, dense_dv_.data(), dv_.data());
    evaluate_refined_only(*stencils_, control_.positions[0].data(), out_.positions[0].data(), du_.data(), dv_.data());
    normals_from_tangents(du_.data(), dv_.data(), out_.normals.data(), 0, out_.normals.size());
    stale_ = false;
    return out_;
  }

  size_t bytes_out() const override { return dense_p_.size() * 3 * sizeof(float); }  // P, du, dv on the device
  std::optional<GpuTimes> gpu_times() const override { return times_; }

 private:
  inline static const Osd::BufferDescriptor kDesc{0, 3, 3};

  void read(Osd::GLVertexBuffer& buffer, float* out) const {
    const gl::Functions& f = ctx_->functions();
    f.BindBuffer(GL_ARRAY_BUFFER, buffer.BindVBO());
    f.GetBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(dense_p_.size() * sizeof(float)), out);
    f.BindBuffer(GL_ARRAY_BUFFER, 0);
  }

  std::shared_ptr<gl::Context> ctx_;
  const ControlMesh control_;
  std::shared_ptr<const LimitStencils> stencils_;  // shared with other runs of the topology
  std::unique_ptr<Osd::GLVertexBuffer> source_, position_, tangent_u_, tangent_v_;
  std::unique_ptr<Osd::GLStencilTableSSBO> table_;
  std::unique_ptr<Osd::GLComputeEvaluator> evaluator_;
  gl::PassTimer timer_;
  GpuTimes times_;
  std::vector<float> du_, dv_;
  std::vector<float> dense_p_, dense_du_, dense_dv_;  // per limit stencil, as the device wrote them
  Tessellation out_;
  bool stale_ = false;
};

class OsdGlCompute final : public Scheme {
 public:
  explicit OsdGlCompute(SubdivisionRule rule) : rule_(rule), info_(limit_stencil_info(rule)) {
    const bool loop = rule == SubdivisionRule::Loop;
    info_.name = loop ? "osd-glcompute-loop" : "osd-glcompute";
    info_.paper = "peer: OpenSubdiv 3.5 Far::LimitStencilTable + Osd::GLComputeEvaluator (EGL, OpenGL 4.3)";
    info_.description = std::string(loop ? "Loop" : "Catmull-Clark") +
                        " limit stencils at the vertices of depth-k refinement, evaluated by a GL compute shader";
    info_.peer = loop ? "osd-stencil-loop" : "osd-stencil";  // the same tables on the CPU
    info_.backends = {Backend::OpenGl};
    // The meshes the methods' large outputs are measured on, for a same-device comparison.
    info_.large_meshes = {loop ? "stanford/bunny" : "stein/sword_quad_dominant"};
  }
  const SchemeInfo& info() const override { return info_; }
  std::optional<std::string> unsupported(const RunRequest& r) const override {
    if (r.level < 1 || r.level > kMaxStencilDepth) return "depth must be 1.." + std::to_string(kMaxStencilDepth);
    if (r.backend != Backend::OpenGl) return std::nullopt;  // the harness says which backends it has
    return opengl_unavailable();
  }
  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& r) const override {
    if (auto why = opengl_unavailable()) throw Unsupported(*why);
    return std::make_unique<OsdGlComputeEvaluation>(mesh, rule_, r.level);
  }

 private:
  SubdivisionRule rule_;
  SchemeInfo info_;
};

}  // namespace

std::unique_ptr<Scheme> make_osd_glcompute(SubdivisionRule rule) { return std::make_unique<OsdGlCompute>(rule); }

}  // namespace sdb
