// Kept for earlier code: the BMFR filter now lives in <bmfr/filters/bmfr_filter.h>.
#pragma once
#include <bmfr/filters/bmfr_filter.h>
