// CPU twin: sweep_point_default() in src/saliency/sweep_kernels.inc
#version 450
#extension GL_GOOGLE_include_directive : require
// meshsal: sweep8 for CPU devices (lavapipe): a lane per point, rows shared by the
// subgroup (see sweep.glsl).
#define FAST8
#define UNIFORM_ROWS
#include "sweep.glsl"
#include "sweep_layout_rows.glsl"
