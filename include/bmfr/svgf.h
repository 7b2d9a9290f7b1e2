// Kept for earlier code: SVGF now lives in <bmfr/filters/svgf.h>.
#pragma once
#include <bmfr/filters/svgf.h>
