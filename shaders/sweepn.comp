// CPU twin: sweep_point_generic() in src/saliency/sweep_kernels.inc
#version 450
#extension GL_GOOGLE_include_directive : require
// meshsal: the sweep for any plan of up to 16 sigmas, specialised per plan (see sweep.glsl).
#include "sweep.glsl"
#include "sweep_layout_subgroup.glsl"
