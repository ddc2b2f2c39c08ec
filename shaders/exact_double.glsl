// meshsal: a float's value as a double, exactly, on any device. The host's double(float) is
// exact; a device may flush float denormals (|x| < 2^-126) to zero when converting (its
// float controls: shaderDenormPreserveFloat32 is optional), so a denormal is rebuilt from
// its bits: its 23-bit integer times 2^-149 (both exact in double). Normal values,
// zeros' signs, infinities and NaNs convert as they are.
double exact_double(float x) {
  const uint b = floatBitsToUint(x);
  if ((b & 0x7f800000u) != 0u) return double(x);
  // 2^-149 from two normal floats: 2^-126 * 2^-23.
  const double ulp = double(uintBitsToFloat(0x00800000u)) * double(uintBitsToFloat(0x34000000u));
  const double m = double(b & 0x007fffffu) * ulp;
  return (b & 0x80000000u) != 0u ? -m : m;
}

dvec3 exact_double3(vec3 v) { return dvec3(exact_double(v.x), exact_double(v.y), exact_double(v.z)); }
