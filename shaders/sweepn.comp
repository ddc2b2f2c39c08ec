#version 450
#extension GL_GOOGLE_include_directive : require
// meshsal: the sweep for up to 16 arbitrary sigmas, one exp each (see sweep.glsl).
#include "sweep.glsl"
