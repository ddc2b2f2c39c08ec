// CPU twin: sweep_point_default() in src/saliency/sweep_kernels.inc
#version 450
#extension GL_GOOGLE_include_directive : require
// meshsal: the sweep for the eight default sigmas {2,3,4,5,6,8,10,12} eps (see sweep.glsl).
#define FAST8
#include "sweep.glsl"
#include "sweep_layout_subgroup.glsl"
