#pragma once
// The progress line long-running subcommands draw on a terminal (reference, realtime, sweep,
// gate): one line on stderr, redrawn in place, with durations as format_seconds writes them.
// Nothing is drawn when stderr is not a terminal (CI logs get only the final summary).

#include <string>

namespace giq::cli {

// "42s", "3m07s", "2h15m"; "?" for a negative (unknown) duration.
std::string format_seconds(double seconds);

class ProgressLine {
 public:
  ProgressLine();  // active when stderr is a terminal
  bool active() const { return active_; }
  // Replaces the line's text (printf-style).
  [[gnu::format(printf, 2, 3)]] void show(const char* format, ...);
  // Clears the line, so that a message printed next starts on an empty line.
  void clear();
  // Ends the line (a newline after the last text), once.
  void finish();

 private:
  bool active_ = false, drawn_ = false;
};

}  // namespace giq::cli
