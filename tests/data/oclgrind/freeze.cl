// The smallest kernel found on which Oclgrind 21.10 stops with "OCLGRIND FATAL ERROR ...
// Unsupported instruction: freeze" when its uninitialised-value check is on
// (docs/portability.md "Oclgrind's uninitialised-value check"). A quotient and a
// remainder of the same operands make LLVM 14 (inside Oclgrind) compute the remainder
// from the quotient through `freeze`, an instruction newer than the plugin; the kernel is
// abandoned and its outputs stay unwritten. out[i] = (i + 1) / 3 + (i + 1) % 3 / 2.
__kernel void k(__global const float4* in, __global float* out) {
  const int n = (int)in[get_global_id(0)].x;
  out[get_global_id(0)] = (float)(n / 3) + 0.5f * (float)(n % 3);
}
