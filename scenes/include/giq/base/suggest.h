#pragma once
// "Did you mean ...?" for a name that is not one of the known ones (an option, a technique, a
// parameter, a view, a metric): the known name nearest in edit distance, when it is near
// enough to be a typo rather than another word.

#include <string>
#include <string_view>
#include <vector>

namespace giq {

// The known name nearest to `typed` by optimal string alignment distance (insertions,
// deletions, substitutions and transpositions of neighbours, ASCII case ignored), when that
// distance is at most max(1, length / 3) of the longer name; else "".
std::string nearest_name(std::string_view typed, const std::vector<std::string>& known);

// "; did you mean 'x'?" with nearest_name's x, or "" when there is none: for the end of a
// message that lists or names what was expected.
std::string did_you_mean(std::string_view typed, const std::vector<std::string>& known);

}  // namespace giq
