// Kept for earlier code: BMFR's settings now live in <bmfr/filters/bmfr_filter.h>.
#pragma once
#include <bmfr/filters/bmfr_filter.h>
