// Kept for earlier code: BMFR's settings now live in <bmfr/filters/bmfr.h>.
#pragma once
#include <bmfr/filters/bmfr.h>
