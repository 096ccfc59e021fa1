#include "core/suggest.hpp"
#include <algorithm>
#include <cctype>

namespace terrace {

namespace {

char folded(char c) {
    return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
}

/// `name` begins with `word`, ignoring case, and `word` is a whole '_'-separated part of it
/// ("dt" of "dt_fs") or at least three letters ("temp" of "temperature").
bool isBeginningOf(std::string_view word, std::string_view name) {
    if (word.empty() || word.size() >= name.size()) return false;
    if (name[word.size()] != '_' && word.size() < 3) return false;
    for (std::size_t i = 0; i < word.size(); ++i)
        if (folded(word[i]) != folded(name[i])) return false;
    return true;
}

} // namespace

int editDistance(std::string_view a, std::string_view b) {
    const std::size_t n = a.size(), m = b.size();
    // Three rows of the dynamic programme: a transposition looks two rows back.
    std::vector<int> before(m + 1), previous(m + 1), current(m + 1);
    for (std::size_t j = 0; j <= m; ++j)
        previous[j] = int(j);
    for (std::size_t i = 1; i <= n; ++i) {
        current[0] = int(i);
        for (std::size_t j = 1; j <= m; ++j) {
            const int cost = folded(a[i - 1]) == folded(b[j - 1]) ? 0 : 1;
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
            if (i > 1 && j > 1 && folded(a[i - 1]) == folded(b[j - 2]) &&
                folded(a[i - 2]) == folded(b[j - 1]))
                current[j] = std::min(current[j], before[j - 2] + 1);
        }
        std::swap(before, previous);
        std::swap(previous, current);
    }
    return previous[m];
}

std::string nearestName(std::string_view word, const std::vector<std::string>& candidates) {
    // Short words allow few edits: any one-letter name is one edit from any other.
    const int allowed = int(word.size() + 1) / 3;
    std::string best;
    int bestDistance = allowed + 1;
    for (const std::string& name : candidates) {
        const int d = isBeginningOf(word, name) ? 0 : editDistance(word, name);
        if (d < bestDistance) best = name, bestDistance = d;
    }
    return best;
}

} // namespace terrace
