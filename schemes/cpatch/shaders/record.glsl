// A patch record in registers: conversion.h's PatchRecord, 28 float3, seven per corner i:
// p*_i, then relative to p*_i the limit point v and tangent points t_0, t_1, then relative to
// p*_0 the interior coefficients: f^i for a bicubic patch (X1, X2 zero), b211, b121, b112 for a
// c-patch.
const int kRecordSize = 28;
const int kP = 0, kV = 1, kT0 = 2, kT1 = 3, kX0 = 4, kX1 = 5, kX2 = 6;

int record_index(int corner, int entry) { return 7 * corner + entry; }

// One of four values by a run-time index, as selects: a register array indexed at run time would
// live in memory (local memory on a GPU, per-lane scratch on lavapipe).
vec3 pick(vec3 a0, vec3 a1, vec3 a2, vec3 a3, int i) { return i == 0 ? a0 : (i == 1 ? a1 : (i == 2 ? a2 : a3)); }
// Entry `entry` (a constant) of corner `corner` (known at run time only).
#define CORNER_ENTRY(record, corner, entry) \
  pick(record[entry], record[7 + (entry)], record[14 + (entry)], record[21 + (entry)], corner)

// Per quad: bits 0-3 forward_sides, bits 4.. the c-patch index + 1 (0: ordinary quad).
uint forward_sides_of(uint info) { return info & 15u; }
int cpatch_index_of(uint info) { return int(info >> 4) - 1; }

// One quad corner's view of its vertex, what a patch is assembled from: p* and, relative to it,
// v, t_0, t_1 (towards corners i+1, i-1), f of the quad's sector, e_0, e_1.
struct CornerData {
  vec3 p, v, t0, t1, f, e0, e1;
};
