// Checks every CUDA call: a failure becomes hdrf::Error naming the call and the reason.
#pragma once

#include <cuda_runtime_api.h>

#include <string>

#include "common/error.h"

#define HDRF_CUDA_CHECK(call)                                                             \
  do {                                                                                    \
    const cudaError_t hdrf_err_ = (call);                                                 \
    if (hdrf_err_ != cudaSuccess)                                                         \
      throw ::hdrf::Error(std::string("CUDA error in ") + #call + " (" + __FILE__ + ":" + \
                          std::to_string(__LINE__) + "): " + cudaGetErrorString(hdrf_err_)); \
  } while (0)

// After a kernel launch: launch errors (bad configuration) surface here.
#define HDRF_CUDA_CHECK_LAUNCH() HDRF_CUDA_CHECK(cudaGetLastError())
