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
