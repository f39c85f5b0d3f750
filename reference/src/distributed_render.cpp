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

// Copies between a tile's pixels and a film.
void store(const WorkUnits& u, const TileState& t, Film& film) {
  const WorkUnits::Rect r = u.rect(tile_of(u, t.unit));
  size_t at = 0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x, ++at) {
      const size_t p = size_t(y) * size_t(u.width) + size_t(x);
      film.pixels[p] = t.pixels[at];
      film.aux[p] = t.aux[at];
    }
}
TileState load(const WorkUnits& u, uint64_t unit, const Film& film) {
  TileState t;
  t.unit = unit;
  const WorkUnits::Rect r = u.rect(tile_of(u, unit));
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const size_t p = size_t(y) * size_t(u.width) + size_t(x);
      t.pixels.push_back(film.pixels[p]);
      t.aux.push_back(film.aux[p]);
    }
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
// checkpoint interval, reporting progress once an interval.
uint64_t work(Link& link, const DistributedJob& job, FrameRenderers& renderers) {
  const WorkUnits units{job.header.first_frame, job.header.last_frame, job.header.settings.width, job.header.settings.height};
  const uint32_t spp = job.header.spp;
  const double interval = job.checkpoint_interval_seconds;
  uint64_t rendered = 0;
  int film_frame = -1;
  Film film;
  std::optional<TileState> finished;
  while (std::optional<TileState> unit = link.next(std::move(finished))) {
    finished.reset();
    const int frame = frame_of(units, unit->unit);
    const Renderer& renderer = renderers.renderer(frame);
    if (frame != film_frame) film = renderer.make_film(), film_frame = frame;
    const WorkUnits::Rect r = units.rect(tile_of(units, unit->unit));
    // Renderer::render's `only` names its 16 x 16 tiles by their top-left corners.
    const auto only = [&r](int x, int y) { return x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1; };
    if (unit->pixels.empty()) {
      renderer.render_aux(film, only);
    } else {
      store(units, *unit, film);
    }
    uint32_t have = spp;
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) have = std::min(have, film.pixels[size_t(y) * size_t(units.width) + size_t(x)].samples);
    uint32_t step = 1;
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
      const double next = double(target - have) * 0.25 * interval / took;
      step = uint32_t(std::clamp(next, 1.0, 2.0 * double(step) + 1.0));
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

class Coordinator {
 public:
  Coordinator(const DistributedJob& job, const std::function<void(int, const Film&)>& done)
      : job_(job), done_(done),
        units_{job.header.first_frame, job.header.last_frame, job.header.settings.width, job.header.settings.height},
        handed_(units_.count(), 0) {}

  bool resume() {
    if (!job_.resume || job_.checkpoint.empty() || !std::filesystem::exists(job_.checkpoint)) return false;
    const Part saved = read_part(job_.checkpoint, PartUse::Checkpoint);
    if (saved.identity != job_.header.identity)
      throw InputError(job_.checkpoint.string(), "--resume",
                       "is the checkpoint of another render: '" + saved.identity + "', not '" + job_.header.identity + "'");
    for (int f : saved.written) {
      written_.push_back(f);
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

  // The next unit: those started before a resume first, then the rest in order.
  std::optional<TileState> next() {
    if (job_.cancel != nullptr && job_.cancel->load()) return std::nullopt;
    if (!restarted_.empty()) {
      TileState t = std::move(restarted_.front());
      restarted_.pop_front();
      return t;
    }
    while (cursor_ < handed_.size() && handed_[cursor_]) ++cursor_;
    if (cursor_ == handed_.size()) return std::nullopt;
    handed_[cursor_] = 1;
    TileState t;
    t.unit = cursor_++;
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
    done_(f, it->second.film);
    written_.insert(std::upper_bound(written_.begin(), written_.end(), f), f);
    frames_.erase(it);
  }

  void checkpoint_if_due() {
    if (job_.checkpoint.empty() || seconds_since(saved_) < job_.checkpoint_interval_seconds) return;
    write_checkpoint();
  }

  void write_checkpoint() {
    if (job_.checkpoint.empty()) return;
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

  // Every frame written: what a completed render must have done.
  bool all_written() const { return frames_.empty() && written_.size() == size_t(units_.last_frame - units_.first_frame + 1); }

 private:
  struct FrameFilm {
    Film film;
    int missing = 0;
    std::vector<uint32_t> tiles;  // those in
  };
  const DistributedJob& job_;
  const std::function<void(int, const Film&)>& done_;
  WorkUnits units_;
  std::vector<uint8_t> handed_;  // per unit: handed out, restored or written
  uint64_t cursor_ = 0;
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

  Coordinator coordinator(job, done);
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
  const auto answer = [&](std::optional<TileState> finished) {
    if (finished) coordinator.finished(std::move(*finished));
    std::optional<TileState> next = coordinator.next();
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
          ranks.send(m->source, kAssign, encode(answer(std::move(t))));
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
          std::optional<TileState> next = answer(std::move(in.finished));
          local_active = next.has_value();
          local.reply(std::move(next));
        }
      }
      if (failure) break;
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
  outcome.completed = job.cancel == nullptr || !job.cancel->load();
  if (outcome.completed && !coordinator.all_written())
    throw std::logic_error("render_across_ranks: every rank signed off before every frame was written");
  if (!outcome.completed) {
    coordinator.write_checkpoint();
  } else if (!job.checkpoint.empty()) {
    std::filesystem::remove(job.checkpoint);
  }
  return outcome;
}

}  // namespace giq::reference
