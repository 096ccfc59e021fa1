#pragma once
// "Did you mean": the known name nearest a misspelt one, for unknown scene keys, choices and
// command-line options. Nearness is the optimal-string-alignment distance (Levenshtein with
// adjacent transpositions, each edit costing 1), case-insensitive, so that "dv" finds "dV" and
// "desnity" finds "density". A name that begins with the misspelt one is near too, when that is
// a whole '_'-separated part of it ("dt" for "dt_fs", "time" for "time_ps": a unit suffix left
// off is the commonest slip, and three edits away) or at least three letters ("temp").
#include <string>
#include <string_view>
#include <vector>

namespace terrace {

/// Edits (insertions, deletions, substitutions, adjacent transpositions) from a to b, ignoring
/// ASCII case.
int editDistance(std::string_view a, std::string_view b);

/// The candidate nearest `word`, or "" when none is near enough to be what was meant: at most
/// (|word| + 1) / 3 edits away (none for one letter), or beginning with it (see above). Ties go
/// to the first listed.
std::string nearestName(std::string_view word, const std::vector<std::string>& candidates);

} // namespace terrace
