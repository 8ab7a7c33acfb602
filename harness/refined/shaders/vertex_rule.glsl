// harness/refined/vertex_rule.h in GLSL, operation for operation (included by the
// uniform-refinement peers' shaders).
const int kSmoothRule = 1, kDartRule = 2, kCreaseRule = 4, kCornerRule = 8;
int vertex_rule(float vs, int sharp) { return vs > 0.0 || sharp > 2 ? kCornerRule : 1 << sharp; }

float parent_mask_weight(int transitions, float transition_sum, float pvs, float cvs) {
  int count = transitions;
  precise float sum = transition_sum;
  if (pvs > 0.0 && cvs <= 0.0) ++count, sum = sum + pvs;
  precise float pw = count == 0 ? 0.0 : sum / float(count);
  return pw > 1.0 ? 1.0 : pw;
}
