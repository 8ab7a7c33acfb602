// A quad's record as pass 1b streamed it out (an ordinary quad's X1, X2 are not stored: zero).
// Needs record.glsl, and buffers.glsl with BINDING_RECORDS unless the includer reads entry i of
// the records elsewhere through RECORD_ENTRY(i) (a vec4).
#ifndef RECORD_ENTRY
#define RECORD_ENTRY(i) records[i]
#endif
void load_record(int quad, bool is_cpatch, out vec3 record[kRecordSize]) {
  [[unroll]] for (int e = 0; e < kRecordSize; ++e)
    record[e] = (!is_cpatch && e % 7 > kX0) ? vec3(0.0) : RECORD_ENTRY(quad * kRecordSize + e).xyz;
}
