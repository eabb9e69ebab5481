// Accessors for the metrics that ship with blocklab, one per file (metrics/<name>.cpp). The registry table in
// metrics/registry.cpp lists them explicitly; the objects are stateless singletons.
#pragma once

#include "metrics/metric.h"

namespace blocklab {

const Metric& log2rgb_metric();      // metrics/log2rgb.cpp     SPECS.md 1a
const Metric& mpsnr_metric();        // metrics/mpsnr.cpp       SPECS.md 1b, fixed stops (astcenc)
const Metric& mpsnr_auto_metric();   // metrics/mpsnr_auto.cpp  SPECS.md 1b, HDR_Toolbox automatic stops
const Metric& psnr_metric();         // metrics/psnr.cpp        SPECS.md 1d, RGB code values
const Metric& psnr_luma_metric();    // metrics/psnr_luma.cpp   SPECS.md 1d, BT.601 luma of code values
const Metric& pu21_psnr_metric();    // metrics/pu21_psnr.cpp   SPECS.md 1c, PU21-PSNR

}  // namespace blocklab
