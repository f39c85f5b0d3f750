#include "giq/reference/distributed_render.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "giq/base/error.h"
#include "binary_record.h"

namespace giq::reference {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

enum Tag : int {
  kRequest = 1,   // worker -> 0: the finished unit, if any; asks for the next
  kProgress = 2,  // worker -> 0: the unit so far, for the checkpoint
  kAssign = 3,    // 0 -> worker: the next unit (with its pixels when it was started before), or none
  kStop = 4,      // worker -> 0: cancelled; the unit so far, for another rank or the checkpoint
};

// One unit's pixels: empty when the unit has not been started.
struct TileState {
  uint64_t unit = 0;
  std::vector<PixelAccumulator> pixels;
  std::vector<PixelAux> aux;
};

void put_tile(std::string& out, const TileState& t) {
  put(out, t.unit);
  put(out, uint64_t(t.pixels.size()));
  if (t.pixels.empty()) return;
  out.append(reinterpret_cast<const char*>(t.pixels.data()), t.pixels.size() * sizeof(PixelAccumulator));
  out.append(reinterpret_cast<const char*>(t.aux.data()), t.aux.size() * sizeof(PixelAux));
}

TileState get_tile(RecordReader& r, const WorkUnits& units) {
  TileState t;
  t.unit = r.get<uint64_t>();
  const uint64_t n = r.get<uint64_t>();
  if (t.unit >= units.count()) r.fail("unit " + std::to_string(t.unit) + " is not one of the render's");
  if (n != 0 && n != units.rect(uint32_t(t.unit % uint64_t(units.tiles_per_frame()))).pixels())
    r.fail("unit " + std::to_string(t.unit) + " arrived with " + std::to_string(n) + " pixels");
  t.pixels.resize(size_t(n));
  t.aux.resize(size_t(n));
  r.bytes(t.pixels.data(), size_t(n) * sizeof(PixelAccumulator));
  r.bytes(t.aux.data(), size_t(n) * sizeof(PixelAux));
  return t;
}

// A message: a flag (whether a tile follows) and the tile.
std::string encode(const std::optional<TileState>& t) {
  std::string out;
  put(out, uint8_t(t.has_value()));
  if (t) put_tile(out, *t);
  return out;
}
std::optional<TileState> decode(const std::string& bytes, const WorkUnits& units) {
  RecordReader r(bytes, bytes.size(), "", "MPI message", "a message from another rank is truncated");
  if (r.get<uint8_t>() == 0) return std::nullopt;
  return get_tile(r, units);
}

int frame_of(const WorkUnits& u, uint64_t unit) { return u.first_frame + int(unit / uint64_t(u.tiles_per_frame())); }
uint32_t tile_of(const WorkUnits& u, uint64_t unit) { return uint32_t(unit % uint64_t(u.tiles_per_frame())); }

// Copies between a unit's pixels and a film (part.h's tile layout).
void store(const WorkUnits& u, const TileState& t, Film& film) {
  copy_tile_in(film, u, tile_of(u, t.unit), t.pixels.data(), t.aux.data());
}
TileState load(const WorkUnits& u, uint64_t unit, const Film& film) {
  TileState t;
  t.unit = unit;
  copy_tile_out(film, u, tile_of(u, unit), t.pixels, t.aux);
  return t;
}
bool complete(const TileState& t, uint32_t spp) {
  return !t.pixels.empty() && std::all_of(t.pixels.begin(), t.pixels.end(), [&](const PixelAccumulator& p) { return p.samples == spp; });
}

// A worker's way to rank 0.
class Link {
 public:
  virtual ~Link() = default;
  // Hands back the finished unit (none the first time) and gets the next, nullopt when none is
  // left.
  virtual std::optional<TileState> next(std::optional<TileState> finished) = 0;
  virtual void progress(TileState state) = 0;
  // Cancelled: gives the unit back as far as it got, and asks for nothing more.
  virtual void stop(TileState state) = 0;
};

class RemoteLink final : public Link {
 public:
  RemoteLink(const Ranks& ranks, const WorkUnits& units) : ranks_(ranks), units_(units) {}
  std::optional<TileState> next(std::optional<TileState> finished) override {
    ranks_.send(0, kRequest, encode(finished));
    const Ranks::Message m = ranks_.receive(0);
    return decode(m.bytes, units_);
  }
  void progress(TileState state) override { ranks_.send(0, kProgress, encode(std::move(state))); }
  void stop(TileState state) override { ranks_.send(0, kStop, encode(std::move(state))); }

 private:
  const Ranks& ranks_;
  const WorkUnits& units_;
};

// Rank 0's render thread and its coordinator, which polls this between MPI messages.
class LocalLink final : public Link {
 public:
  std::optional<TileState> next(std::optional<TileState> finished) override {
    std::unique_lock lock(m_);
    request_ = true;
    finished_ = std::move(finished);
    cv_.wait(lock, [&] { return replied_; });
    replied_ = false;
    return std::move(reply_);
  }
  void progress(TileState state) override {
    const std::lock_guard lock(m_);
    progress_.push_back(std::move(state));
  }
  void stop(TileState state) override {
    const std::lock_guard lock(m_);
    stopped_ = std::move(state);
  }

  // The coordinator's side: the reports so far, and the request or the stop if one waits.
  struct Inbox {
    std::vector<TileState> progress;
    bool request = false;
    std::optional<TileState> finished, stopped;
  };
  Inbox take() {
    const std::lock_guard lock(m_);
    Inbox in{std::move(progress_), request_, std::move(finished_), std::move(stopped_)};
    progress_.clear();
    request_ = false;
    finished_.reset();
    stopped_.reset();
    return in;
  }
  void reply(std::optional<TileState> next) {
    {
      const std::lock_guard lock(m_);
      reply_ = std::move(next);
      replied_ = true;
    }
    cv_.notify_one();
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<TileState> progress_;
  bool request_ = false, replied_ = false;
  std::optional<TileState> finished_, reply_, stopped_;
};

// Renders the units the link hands out, each to spp in passes of about a quarter of the
// checkpoint interval, reporting progress once an interval. The pass size carries over from
// unit to unit, so that a short unit is rendered in one pass (a pass over a unit costs a
// walk over the frame's tiles and a task arena).
uint64_t work(Link& link, const DistributedJob& job, FrameRenderers& renderers) {
  const WorkUnits units{job.header.first_frame, job.header.last_frame, job.header.settings.width, job.header.settings.height};
  const uint32_t spp = job.header.spp;
  const double interval = job.checkpoint_interval_seconds;
  uint64_t rendered = 0;
  Film film;
  double per_sample = 0.0;  // seconds a sample of a unit took last
  std::optional<TileState> finished;
  while (std::optional<TileState> unit = link.next(std::move(finished))) {
    finished.reset();
    const Renderer& renderer = renderers.renderer(frame_of(units, unit->unit));
    // One film for every unit of every frame: each unit's pixels start afresh.
    if (film.pixels.empty()) film = renderer.make_film();
    const WorkUnits::Rect r = units.rect(tile_of(units, unit->unit));
    // Renderer::render's `only` names its 16 x 16 tiles by their top-left corners.
    const auto only = [&r](int x, int y) { return x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1; };
    if (unit->pixels.empty()) {
      PixelAccumulator fresh;
      fresh.block = job.header.settings.block();
      for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
          const size_t p = size_t(y) * size_t(units.width) + size_t(x);
          film.pixels[p] = fresh, film.aux[p] = PixelAux{};
        }
      renderer.render_aux(film, only);
    } else {
      store(units, *unit, film);
    }
    uint32_t have = spp;
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) have = std::min(have, film.pixels[size_t(y) * size_t(units.width) + size_t(x)].samples);
    uint32_t step = per_sample > 0.0 ? uint32_t(std::clamp(0.25 * interval / per_sample, 1.0, double(spp))) : 1;
    Clock::time_point reported = Clock::now();
    bool cancelled = false;
    while (have < spp) {
      const uint32_t target = uint32_t(std::min<uint64_t>(spp, uint64_t(have) + step));
      const Clock::time_point start = Clock::now();
      if (!renderer.render(film, target, job.cancel, nullptr, only)) {
        cancelled = true;
        break;
      }
      const double took = std::max(1e-4, seconds_since(start));
      per_sample = took / double(target - have);
      step = uint32_t(std::clamp(0.25 * interval / per_sample, 1.0, 2.0 * double(step) + 1.0));
      have = target;
      if (seconds_since(reported) >= interval && have < spp) {
        link.progress(load(units, unit->unit, film));
        reported = Clock::now();
      }
    }
    if (cancelled) {
      link.stop(load(units, unit->unit, film));
      return rendered;
    }
    finished = load(units, unit->unit, film);
    ++rendered;
  }
  return rendered;
}

// Rank 0's writer: hands each complete frame's film to `done` on a thread of its own, so that
// writing an EXR never keeps the coordinator from answering the ranks.
class FrameWriter {
 public:
  explicit FrameWriter(const std::function<void(int, const Film&)>& done) : done_(done), thread_([this] { run(); }) {}
  ~FrameWriter() {
    if (thread_.joinable()) {
      {
        const std::lock_guard lock(m_);
        closed_ = true;
      }
      cv_.notify_one();
      thread_.join();
    }
  }
  void push(int frame, Film film) {
    {
      const std::lock_guard lock(m_);
      queue_.emplace_back(frame, std::move(film));
    }
    cv_.notify_one();
  }
  // The frames written since the last call.
  std::vector<int> take_written() {
    const std::lock_guard lock(m_);
    std::vector<int> w = std::move(written_);
    written_.clear();
    return w;
  }
  // Waits until every frame pushed is written; rethrows what writing one threw.
  void finish() {
    {
      const std::lock_guard lock(m_);
      closed_ = true;
    }
    cv_.notify_one();
    thread_.join();
    if (failure_) std::rethrow_exception(failure_);
  }
  bool failed() {
    const std::lock_guard lock(m_);
    return failure_ != nullptr;
  }

 private:
  void run() {
    for (;;) {
      std::unique_lock lock(m_);
      cv_.wait(lock, [&] { return closed_ || !queue_.empty(); });
      if (queue_.empty()) return;
      auto [frame, film] = std::move(queue_.front());
      queue_.pop_front();
      lock.unlock();
      try {
        if (!failure_) done_(frame, film);
      } catch (...) {
        lock.lock();
        failure_ = std::current_exception();
        continue;
      }
      lock.lock();
      written_.push_back(frame);
    }
  }

  const std::function<void(int, const Film&)>& done_;
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<std::pair<int, Film>> queue_;
  std::vector<int> written_;
  bool closed_ = false;
  std::exception_ptr failure_;
  std::thread thread_;  // last: started once the rest is constructed
};

class Coordinator {
 public:
  // ranks: how many ask for units. Frames are opened a few at a time: enough for every rank to
  // have about 4 units of an open frame, and one more, so that rank 0 holds few frames' films.
  Coordinator(const DistributedJob& job, int ranks, FrameWriter& writer)
      : job_(job), writer_(writer),
        units_{job.header.first_frame, job.header.last_frame, job.header.settings.width, job.header.settings.height},
        handed_(units_.count(), 0),
        complete_(size_t(units_.last_frame - units_.first_frame + 1), 0),
        max_open_(size_t(4 * ranks + units_.tiles_per_frame() - 1) / size_t(units_.tiles_per_frame()) + 1) {}

  bool resume() {
    if (!job_.resume || job_.checkpoint.empty() || !std::filesystem::exists(job_.checkpoint)) return false;
    const Part saved = read_part(job_.checkpoint, PartUse::Checkpoint);
    if (saved.identity != job_.header.identity)
      throw InputError(job_.checkpoint.string(), "--resume",
                       "is the checkpoint of another render: '" + saved.identity + "', not '" + job_.header.identity + "'");
    for (int f : saved.written) {
      written_.push_back(f);
      complete_[size_t(f - units_.first_frame)] = 1;
      for (int t = 0; t < units_.tiles_per_frame(); ++t) handed_[units_.unit(f, t)] = 1;
    }
    for (const PartFrame& pf : saved.frames) {
      size_t at = 0;
      for (uint32_t t : pf.tiles) {
        TileState s;
        s.unit = units_.unit(pf.frame, int(t));
        const size_t n = units_.rect(t).pixels();
        s.pixels.assign(pf.pixels.begin() + ptrdiff_t(at), pf.pixels.begin() + ptrdiff_t(at + n));
        s.aux.assign(pf.aux.begin() + ptrdiff_t(at), pf.aux.begin() + ptrdiff_t(at + n));
        at += n;
        handed_[s.unit] = 1;
        if (complete(s, job_.header.spp)) {
          finished(std::move(s));
        } else {
          partial_[s.unit] = s;
          restarted_.push_back(std::move(s));
        }
      }
    }
    return true;
  }

  // The next unit for `worker` (a rank): units started before a resume or a stop first; then
  // the next of the frame the worker is on, so that a rank poses its scene and builds its BVH
  // for few frames; a worker whose frame has none left starts the first frame no one has
  // started, or, when every frame has started, helps the one with the most units left.
  std::optional<TileState> next(int worker) {
    if (job_.cancel != nullptr && job_.cancel->load()) return std::nullopt;
    if (!restarted_.empty()) {
      TileState t = std::move(restarted_.front());
      restarted_.pop_front();
      return t;
    }
    if (pending_.empty()) {  // once, after resume() marked what needs no rendering
      const int frames = units_.last_frame - units_.first_frame + 1;
      pending_.resize(size_t(frames));
      started_.assign(size_t(frames), 0);
      for (uint64_t u = 0; u < handed_.size(); ++u) {
        const size_t f = size_t(u / uint64_t(units_.tiles_per_frame()));
        if (handed_[u]) started_[f] = 1;
        else pending_[f].push_back(u);
      }
    }
    size_t& f = frame_of_worker_.try_emplace(worker, pending_.size()).first->second;
    if (f >= pending_.size() || pending_[f].empty()) {
      const size_t none = pending_.size();
      f = none;
      size_t open = 0;  // started and not yet complete: rank 0 holds their films
      for (size_t k = 0; k < pending_.size(); ++k) open += started_[k] && !complete_[k];
      if (open < max_open_)
        for (size_t k = 0; k < pending_.size() && f == none; ++k)
          if (!started_[k] && !pending_[k].empty()) f = k;
      for (size_t k = 0; k < pending_.size() && open >= max_open_; ++k)
        if (started_[k] && !pending_[k].empty() && (f == none || pending_[k].size() > pending_[f].size())) f = k;
      for (size_t k = 0; k < pending_.size() && f == none; ++k)
        if (!pending_[k].empty()) f = k;
      if (f == none) return std::nullopt;
      started_[f] = 1;
    }
    TileState t;
    t.unit = pending_[f].front();
    pending_[f].pop_front();
    return t;
  }

  void progress(TileState t) { partial_[t.unit] = std::move(t); }

  // A rank stopped: its unit goes to the next rank that asks, and meanwhile to the checkpoint.
  void stopped(TileState t) {
    partial_[t.unit] = t;
    restarted_.push_front(std::move(t));
  }

  void finished(TileState t) {
    partial_.erase(t.unit);
    const int f = frame_of(units_, t.unit);
    auto [it, fresh] = frames_.try_emplace(f);
    if (fresh) {
      it->second.film = Film(units_.width, units_.height, job_.header.settings.block());
      it->second.missing = units_.tiles_per_frame();
    }
    store(units_, t, it->second.film);
    it->second.tiles.push_back(tile_of(units_, t.unit));
    if (--it->second.missing > 0) return;
    complete_[size_t(f - units_.first_frame)] = 1;
    writer_.push(f, std::move(it->second.film));
    frames_.erase(it);
  }

  void checkpoint_if_due() {
    if (job_.checkpoint.empty() || seconds_since(saved_) < job_.checkpoint_interval_seconds) return;
    write_checkpoint();
  }

  void write_checkpoint() {
    if (job_.checkpoint.empty()) return;
    for (int f : writer_.take_written()) written_.insert(std::upper_bound(written_.begin(), written_.end(), f), f);
    Part p = job_.header;
    p.shard = {1, 1};
    p.written = written_;
    std::map<int, std::map<uint32_t, TileState>> tiles;  // frame, tile: ascending, as part.h wants
    for (const auto& [f, ff] : frames_)
      for (uint32_t t : ff.tiles) tiles[f][t] = load(units_, units_.unit(f, int(t)), ff.film);
    for (const auto& [u, s] : partial_) tiles[frame_of(units_, u)][tile_of(units_, u)] = s;
    for (auto& [f, by_tile] : tiles) {
      PartFrame pf;
      pf.frame = f;
      for (auto& [t, s] : by_tile) {
        pf.tiles.push_back(t);
        pf.pixels.insert(pf.pixels.end(), s.pixels.begin(), s.pixels.end());
        pf.aux.insert(pf.aux.end(), s.aux.begin(), s.aux.end());
      }
      p.frames.push_back(std::move(pf));
    }
    write_part(job_.checkpoint, p);
    saved_ = Clock::now();
  }

  // Every frame complete: what a completed render must have done.
  bool all_complete() const { return frames_.empty() && std::all_of(complete_.begin(), complete_.end(), [](uint8_t c) { return c != 0; }); }

 private:
  struct FrameFilm {
    Film film;
    int missing = 0;
    std::vector<uint32_t> tiles;  // those in
  };
  const DistributedJob& job_;
  FrameWriter& writer_;
  WorkUnits units_;
  std::vector<uint8_t> handed_;  // per unit: restored or written by resume()
  std::vector<std::deque<uint64_t>> pending_;  // per frame: the units not handed out yet
  std::vector<uint8_t> started_;               // per frame: a unit was handed out or restored
  std::vector<uint8_t> complete_;              // per frame: every tile in
  size_t max_open_;                            // frames started at once, at most while others wait
  std::map<int, size_t> frame_of_worker_;      // the frame each worker is on
  std::deque<TileState> restarted_;
  std::map<uint64_t, TileState> partial_;  // the latest progress of units being rendered
  std::map<int, FrameFilm> frames_;
  std::vector<int> written_;
  Clock::time_point saved_ = Clock::now();
};

}  // namespace

DistributedOutcome render_across_ranks(const Ranks& ranks, const DistributedJob& job, FrameRenderers& renderers,
                                       const std::function<void(int frame, const Film& film)>& done) {
  DistributedOutcome outcome;
  const WorkUnits units{job.header.first_frame, job.header.last_frame, job.header.settings.width, job.header.settings.height};
  if (ranks.rank() != 0) {
    RemoteLink link(ranks, units);
    outcome.units = work(link, job, renderers);
    outcome.completed = job.cancel == nullptr || !job.cancel->load();
    return outcome;
  }

  FrameWriter writer(done);
  Coordinator coordinator(job, ranks.size(), writer);
  outcome.resumed = coordinator.resume();
  LocalLink local;
  std::exception_ptr failure;
  std::thread render([&] {
    try {
      outcome.units = work(local, job, renderers);
    } catch (...) {
      failure = std::current_exception();
    }
  });
  // Every worker signs off by asking for a unit when none is left.
  int active = ranks.size();
  bool local_active = true;
  const auto answer = [&](std::optional<TileState> finished, int source) {
    if (finished) coordinator.finished(std::move(*finished));
    std::optional<TileState> next = coordinator.next(source);
    if (!next) --active;
    return next;
  };
  try {
    while (active > 0) {
      bool idle = true;
      if (std::optional<Ranks::Message> m = ranks.poll()) {
        idle = false;
        std::optional<TileState> t = decode(m->bytes, units);
        if (m->tag == kProgress && t) {
          coordinator.progress(std::move(*t));
        } else if (m->tag == kStop && t) {
          coordinator.stopped(std::move(*t));
          --active;
        } else if (m->tag == kRequest) {
          ranks.send(m->source, kAssign, encode(answer(std::move(t), m->source)));
        }
      }
      if (local_active) {
        LocalLink::Inbox in = local.take();
        for (TileState& t : in.progress) coordinator.progress(std::move(t)), idle = false;
        if (in.stopped) {
          coordinator.stopped(std::move(*in.stopped));
          --active;
          local_active = false;
        }
        if (in.request) {
          idle = false;
          std::optional<TileState> next = answer(std::move(in.finished), 0);
          local_active = next.has_value();
          local.reply(std::move(next));
        }
      }
      if (failure) break;
      if (writer.failed()) writer.finish();  // rethrows
      coordinator.checkpoint_if_due();
      if (idle) std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
  } catch (...) {
    if (!failure) failure = std::current_exception();
  }
  if (failure) {
    // The render thread may wait for a reply that will not come; the caller ends the process.
    render.detach();
    std::rethrow_exception(failure);
  }
  render.join();
  writer.finish();
  outcome.completed = job.cancel == nullptr || !job.cancel->load();
  if (outcome.completed && !coordinator.all_complete())
    throw std::logic_error("render_across_ranks: every rank signed off before every frame was complete");
  if (!outcome.completed) {
    coordinator.write_checkpoint();
  } else if (!job.checkpoint.empty()) {
    std::filesystem::remove(job.checkpoint);
  }
  return outcome;
}

}  // namespace giq::reference
