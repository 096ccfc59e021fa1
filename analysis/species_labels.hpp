#pragma once
// Which species each body of a mixture belongs to, as the analysis needs it: the species' names
// (Scene::species, in its order; they name the CSV columns) and body i's species index, i in the
// scene's numbering. A body's species never changes during a run, so the labels are given once,
// when the analysis is built, and are not part of its restart state. Empty for a scene of one
// kind of body: the analysis then writes exactly what it wrote before mixtures existed.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace terrace::analysis {

struct SpeciesLabels {
    std::vector<std::string> names;   // species a's name, a = 0 … S − 1
    std::vector<std::int32_t> ofBody; // body i's species, i = 0 … N − 1
    // Rods among spheres: species a's axes never move (a sphere's), so its bodies stay out of the
    // OACF; empty where no species is so (a mixture of spheres has no OACF at all).
    std::vector<bool> fixedAxis;

    bool empty() const { return names.empty(); }
    int count() const { return static_cast<int>(names.size()); }

    /// How many bodies of each species.
    std::vector<long> bodiesPerSpecies() const {
        std::vector<long> n(names.size(), 0);
        for (const std::int32_t a : ofBody)
            ++n[static_cast<std::size_t>(a)];
        return n;
    }

    /// std::invalid_argument unless these are labels of `bodies` bodies (or empty): two species
    /// or more, every index one of them.
    void check(int bodies) const {
        if (empty()) {
            if (!ofBody.empty())
                throw std::invalid_argument("analysis: species indices given without names");
            return;
        }
        if (names.size() < 2)
            throw std::invalid_argument("analysis: a mixture needs two species or more");
        if (!fixedAxis.empty() && fixedAxis.size() != names.size())
            throw std::invalid_argument("analysis: " + std::to_string(fixedAxis.size()) +
                                        " fixed-axis flags for " + std::to_string(names.size()) +
                                        " species");
        if (ofBody.size() != static_cast<std::size_t>(bodies))
            throw std::invalid_argument("analysis: " + std::to_string(ofBody.size()) +
                                        " species indices for " + std::to_string(bodies) +
                                        " bodies");
        for (std::size_t i = 0; i < ofBody.size(); ++i)
            if (ofBody[i] < 0 || ofBody[i] >= count())
                throw std::invalid_argument("analysis: body " + std::to_string(i) +
                                            " has species " + std::to_string(ofBody[i]) +
                                            ", not one of the " + std::to_string(count()));
    }
};

/// The index of the unordered pair (a, b) of S species in the order AA, AB, …, A_S, BB, …:
/// a ≤ b after swapping, S(S+1)/2 pairs in all.
inline int speciesPairIndex(int a, int b, int species) {
    if (a > b) std::swap(a, b);
    return a * species - a * (a - 1) / 2 + (b - a);
}

} // namespace terrace::analysis
