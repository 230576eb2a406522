// The smallest kernel found on which Oclgrind 21.10 crashes (SIGSEGV) with its
// uninitialised-value check on (docs/portability.md "Oclgrind's uninitialised-value check").
// Clang (LLVM 14, inside Oclgrind) builds the float3 from the loaded float4 in[1] with
//   shufflevector <4 x float> %v, <4 x float> poison, <3 x i32> <i32 0, i32 undef, i32 undef>
// whose undef lanes insertelement then overwrites: valid IR, a valid kernel. The plugin
// compares the mask lane with llvm::Value::UndefValueVal (a value-kind number) instead of
// -1, so it takes the undef lane for a lane of the second operand (poison) and reads that
// operand's shadow at a negative offset. With in[i] = (i + 1, 0, 0, 0): out[i] = 2^2 + 3^2 + 4^2 = 29.
__kernel void k(__global const float4* in, __global float* out) {
  const float3 v = (float3)(in[1].x, in[2].x, in[3].x);
  out[get_global_id(0)] = dot(v, v);
}
