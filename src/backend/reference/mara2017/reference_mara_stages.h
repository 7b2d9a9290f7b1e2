// Mara 2017's host pipeline: every stage timed, each a plain parallel loop over the stage
// bodies of filters/mara2017/mara_stages.h. The CPU backend replaces the stages it runs faster.
#pragma once
#include "filters/mara2017/mara_passes.h"

namespace bmfr::reference {

class HostMaraPipeline : public HostPasses<Mara2017Settings, MaraBuffers> {
  public:
    void allocate(int w, int h, const Mara2017Settings& s, int threads) override {
        HostPasses::allocate(w, h, s, threads);
        buffers.tables.reserve(s);
    }
    PassCounters run(const MaraPassContext& ctx, StageTimes& times) final;

  protected:
    /// Input and stage 3 (matte temporal); returns the non-finite input values replaced.
    virtual int64_t matteTemporal(const MaraPassContext& ctx, const MaraFrame& f);
    /// Stage 4 into f.matteHistory.
    virtual void preBilateral(const MaraPassContext& ctx, const MaraFrame& f);
    /// Stage 5 into f.radius.
    virtual void disocclusion(const MaraPassContext& ctx, const MaraFrame& f);
    /// Stage 6 into f.median.
    virtual void median(const MaraPassContext& ctx, const MaraFrame& f);
    /// Stage 7 of `src` into f.matteOut.
    virtual void matteBilateral(const MaraPassContext& ctx, const MaraFrame& f, const float* src);
    /// Stage 8 into f.glossyTemporal and f.glossyHistory.
    virtual void glossyTemporal(const MaraPassContext& ctx, const MaraFrame& f);
    /// Stages 9 and 10 from f.glossyTemporal into f.glossyOut.
    virtual void glossyBilateral(const MaraPassContext& ctx, const MaraFrame& f);
    /// The composition into f.composed.
    virtual void compose(const MaraPassContext& ctx, const MaraFrame& f);
};

} // namespace bmfr::reference
