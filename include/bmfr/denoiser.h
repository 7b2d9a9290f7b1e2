// Kept for earlier code: the BMFR filter now lives in <bmfr/filters/bmfr.h>.
#pragma once
#include <bmfr/filters/bmfr.h>
