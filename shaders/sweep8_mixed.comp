// CPU twin: sweep_point_default() in src/saliency/sweep_kernels.inc
#version 450
#extension GL_GOOGLE_include_directive : require
// meshsal: sweep8 in mixed precision (float distances, weights and chunk sums folded into
// doubles; see sweep.glsl), a subgroup per point.
#define FAST8
#define MIXED
#include "sweep.glsl"
#include "sweep_layout_subgroup.glsl"
