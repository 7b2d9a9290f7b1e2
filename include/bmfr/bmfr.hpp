// bmfr: real-time reconstruction of 1-spp path-traced frame sequences. The C++ API in one
// header: frames, the filter interface and registry, and every filter (the C API: <bmfr/bmfr.h>).
#pragma once
#include <bmfr/device.h>
#include <bmfr/error.h>
#include <bmfr/features.h>
#include <bmfr/filter.h>
#include <bmfr/filters/bmfr_filter.h>
#include <bmfr/filters/mara2017_filter.h>
#include <bmfr/filters/svgf_filter.h>
#include <bmfr/filters/walr_filter.h>
#include <bmfr/frame.h>
#include <bmfr/temporal_settings.h>
#include <bmfr/version.h>
