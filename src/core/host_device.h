// Marks math usable from both CPU and (future) CUDA code, as pbrt-v4's PBRT_CPU_GPU.
#pragma once
#if defined(__CUDACC__)
#define BMFR_HD __host__ __device__ inline
#else
#define BMFR_HD inline
#endif
