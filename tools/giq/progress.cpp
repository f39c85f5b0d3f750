#include "progress.h"

#include <unistd.h>

#include <cstdarg>
#include <cstdio>

namespace giq::cli {

std::string format_seconds(double s) {
  char b[32];
  if (s < 0.0) return "?";
  if (s < 120.0)
    std::snprintf(b, sizeof b, "%.0fs", s);
  else if (s < 7200.0)
    std::snprintf(b, sizeof b, "%dm%02ds", int(s) / 60, int(s) % 60);
  else
    std::snprintf(b, sizeof b, "%dh%02dm", int(s) / 3600, (int(s) / 60) % 60);
  return b;
}

ProgressLine::ProgressLine() : active_(::isatty(STDERR_FILENO) != 0) {}

void ProgressLine::show(const char* format, ...) {
  if (!active_) return;
  std::fputs("\r\033[K", stderr);
  va_list args;
  va_start(args, format);
  std::vfprintf(stderr, format, args);
  va_end(args);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressLine::clear() {
  if (active_ && drawn_) std::fputs("\r\033[K", stderr);
}

void ProgressLine::finish() {
  if (active_ && drawn_) std::fputs("\n", stderr);
  drawn_ = false;
}

}  // namespace giq::cli
