#pragma once
// Frames of a sequence as every command names them: one file per frame, `frame_NNNN.exr`
// (`giq realtime`'s output, the goldens, the gate's and sweeps' renders), and frame ranges
// written "A:B" (first and last, inclusive).

#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace giq {

// "frame_0007.exr" for frame 7.
std::string frame_file(int frame);
// The same name as a pattern for `giq score` ("frame_%04d.exr").
inline constexpr const char* kFramePattern = "frame_%04d.exr";

// "A:B" with 0 <= A <= B, two decimal integers and nothing else; nullopt otherwise.
std::optional<std::pair<int, int>> parse_frame_range(std::string_view text);
// "A:B".
std::string frame_range(int first, int last);

}  // namespace giq
