// bmfr: real-time reconstruction of 1-spp path-traced frame sequences (BMFR, Koskela et al. 2019).
#pragma once
#include <bmfr/denoiser.h>
#include <bmfr/error.h>
#include <bmfr/features.h>
#include <bmfr/filter.h>
#include <bmfr/frame.h>
#include <bmfr/settings.h>
#include <bmfr/svgf.h>
