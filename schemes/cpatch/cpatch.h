// The c-patch schemes: Ni, Yeo, Myles, Goel, Peters 2008, "GPU Smoothing of Quad Meshes".
// Ordinary quads become bicubic Bezier patches, extraordinary quads c-patches (24 coefficients,
// four quartic triangular pieces); see README.md in this folder.
#pragma once

#include <memory>
#include <vector>

#include "harness/core/scheme.h"

namespace sdb {

// cpatch-2pass: conversion pass (Tables 1, 2) then evaluation pass (Table 3); cpu, cpu-mt, vulkan.
const SchemeInfo& cpatch_2pass_info();
// cpatch-1pass (conversion and evaluation in one geometry-shader pass, Section 4) and cpatch-tess
// (Table 2 in the tessellation control stage, evaluation after the hardware tessellator, Section
// 6's outlook): vulkan only.
const SchemeInfo& cpatch_1pass_info();
const SchemeInfo& cpatch_tess_info();

// cpatch-2pass, cpatch-1pass, cpatch-tess (in this order).
std::vector<std::unique_ptr<Scheme>> make_cpatch_schemes();

}  // namespace sdb
