// Kept for earlier code: SVGF now lives in <bmfr/filters/svgf_filter.h>.
#pragma once
#include <bmfr/filters/svgf_filter.h>
