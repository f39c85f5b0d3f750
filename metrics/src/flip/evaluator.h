#pragma once
// FLIP on planar RGB buffers: the public hdr_flip / ldr_flip (giq/metrics/flip.h) unpack a
// giq::image::Image into this; benchmarks and tests that hold raw buffers call it directly.

#include "error_map.h"
#include "giq/metrics/flip.h"

namespace giq::metrics::flip {

// hdr = true: HDR-FLIP with the exposure range of `options` (chosen from the reference where
// unset); hdr = false: LDR-FLIP on the input clamped to [0, 1]. Throws InputError for an
// invalid pixels_per_degree or exposure range.
FlipResult evaluate(const ImagePair& pair, bool hdr, const FlipOptions& options);

}  // namespace giq::metrics::flip
