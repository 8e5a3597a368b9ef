// The host/device function macro: per-element functions written once and compiled by
// the C++ compiler for the CPU backend and by nvcc for the CUDA backend.
#pragma once

#if defined(__CUDACC__)
#define HDRF_HD __host__ __device__ __forceinline__
#define HDRF_DEVICE_CODE 1
#else
#define HDRF_HD inline
#define HDRF_DEVICE_CODE 0
#endif

// Unrolls the loop that follows in device code (so that small fixed-size arrays live in
// registers rather than in slow local memory); nothing on the host.
#if defined(__CUDA_ARCH__)
#define HDRF_UNROLL _Pragma("unroll")
#else
#define HDRF_UNROLL
#endif

// Inlines a small lambda on the host (nvcc inlines device lambdas itself), and unrolls a short
// loop on both, for per-element code whose loop indices should become constants.
#if defined(__CUDACC__)
#define HDRF_INLINE_LAMBDA
#else
#define HDRF_INLINE_LAMBDA __attribute__((always_inline))
#endif
#if defined(__CUDA_ARCH__)
#define HDRF_UNROLL_HOST _Pragma("unroll")
#elif defined(__CUDACC__)
#define HDRF_UNROLL_HOST  // nvcc's host pass: its front end does not know GCC's pragma
#else
#define HDRF_UNROLL_HOST _Pragma("GCC unroll 8")
#endif
