// The CPU backend's Mara 2017 input pass, stage 3 (matte temporal), stage 8 (glossy
// temporal) and the composition, eight pixels at a time, with the reference stages' bits: the same
// operations in the same order, the same counts.
#pragma once
#include "filters/mara2017/mara_stages.h"

namespace bmfr::cpu {

/// maraInputPixel over rows [y0, y1); returns the non-finite input values replaced.
int64_t maraInputRows(const MaraFrame& f, long y0, long y1);

/// maraMatteTemporalPixel over rows [y0, y1) (the input pass done for the whole frame: the
/// clamp box reads the neighbouring rows' matte).
void maraMatteTemporalRows(const MaraFrame& f, long y0, long y1);

/// maraGlossyTemporalPixel over rows [y0, y1).
void maraGlossyTemporalRows(const MaraFrame& f, long y0, long y1);

/// maraComposePixel over rows [y0, y1).
void maraComposeRows(const MaraFrame& f, long y0, long y1);

} // namespace bmfr::cpu
