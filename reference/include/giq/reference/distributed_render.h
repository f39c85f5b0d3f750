#pragma once
// One render across MPI ranks (ranks.h): `mpirun -n R giq reference ... --spp N` writes the
// files a single process would have written, bit for bit (docs/reference.md, "MPI").
//
// The work units are part.h's: frame-major 64 x 64 tiles. Rank 0 hands them out one at a time
// to whichever rank asks next, so faster ranks take more, and every rank, rank 0 included (on
// a second thread), renders the units it gets to spp and sends each back whole. A rank stays
// on its frame while the frame has units left, so that it poses the scene and builds a BVH
// for few frames; a few frames are open at a time, so that rank 0 holds few films. Rank 0 puts
// the tiles into their frame's film and hands the film to a writer thread as soon as its last
// tile is in. One process accumulates every sample of a pixel, in index order (a unit never splits
// a pixel: part.h), so each film has the bits of a single-process render whoever rendered it.
//
// Checkpoints: every rank reports its unit's progress each checkpoint interval, and rank 0
// writes the tiles it holds, complete or partial, with the frames already written, to one file
// in part.h's format. --resume hands the partial tiles out first, accumulators and all, so a
// rank killed mid-render costs at most one interval, and the number of ranks may change
// between runs.

#include <atomic>
#include <filesystem>
#include <functional>

#include "giq/reference/film.h"
#include "giq/reference/part.h"
#include "giq/reference/ranks.h"
#include "giq/reference/renderer.h"

namespace giq::reference {

// Each rank's renderers, one frame at a time.
class FrameRenderers {
 public:
  virtual ~FrameRenderers() = default;
  // The renderer of `frame`, valid until the next call.
  virtual const Renderer& renderer(int frame) = 0;
};

struct DistributedJob {
  // What the checkpoint records: identity, scene, settings, spp, frames (no tiles).
  Part header;
  std::filesystem::path checkpoint;  // empty: none
  double checkpoint_interval_seconds = 60.0;
  bool resume = false;  // continue from `checkpoint` when it exists
  const std::atomic<bool>* cancel = nullptr;
};

struct DistributedOutcome {
  bool completed = false;  // false: cancelled; rank 0 wrote a checkpoint when it has a path
  bool resumed = false;
  uint64_t units = 0;  // rendered by this rank (rank 0: by its render thread)
};

// Runs on every rank of `ranks`. On rank 0 `done` gets each frame's film, in the order frames
// complete, on a writer thread of its own (one call at a time). Throws InputError on rank 0
// for a checkpoint of another render; the caller ends every rank (Ranks::abort) on any
// exception.
DistributedOutcome render_across_ranks(const Ranks& ranks, const DistributedJob& job, FrameRenderers& renderers,
                                       const std::function<void(int frame, const Film& film)>& done);

}  // namespace giq::reference
