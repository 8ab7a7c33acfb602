// A quad's record as pass 1b streamed it out (an ordinary quad's X1, X2 are not stored: zero).
// Needs buffers.glsl with BINDING_RECORDS, and record.glsl.
void load_record(int quad, bool is_cpatch, out vec3 record[kRecordSize]) {
  [[unroll]] for (int e = 0; e < kRecordSize; ++e)
    record[e] = (!is_cpatch && e % 7 > kX0) ? vec3(0.0) : records[quad * kRecordSize + e].xyz;
}
