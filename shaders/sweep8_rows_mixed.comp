// CPU twin: sweep_point_default() in src/saliency/sweep_kernels.inc
#version 450
#extension GL_GOOGLE_include_directive : require
// meshsal: sweep8_rows in mixed precision (see sweep.glsl): a lane per point, rows shared
// by the subgroup (CPU devices).
#define FAST8
#define MIXED
#define UNIFORM_ROWS
#include "sweep.glsl"
#include "sweep_layout_rows.glsl"
