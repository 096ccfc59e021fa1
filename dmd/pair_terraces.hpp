#pragma once
// The terrace index of every interacting pair, kept explicitly (DESIGN.md "Terraced potential";
// the "capture map" of Thomson, Lue & Bannerman, J. Chem. Phys. 140, 034105 (2014)). An event
// leaves U exactly on a level, where re-deriving the terrace from U is a coin toss; the engine
// therefore changes an index only when it applies a transmission. Pairs not listed are on
// terrace 0. Each body keeps a short list of (partner, index); in a dense liquid that is ~10
// entries, scanned linearly, which beats a hash map on cache misses.
#include <cstdint>
#include <vector>

namespace terrace::dmd {

class PairTerraces {
public:
    explicit PairTerraces(int nBodies) : byBody_(nBodies) {}

    int get(int i, int j) const {
        for (const Entry& e : byBody_[i])
            if (e.partner == j) return e.terrace;
        return 0;
    }

    void set(int i, int j, int terrace) {
        setOne(i, j, terrace);
        setOne(j, i, terrace);
    }

    /// f(i, j, terrace) once per listed pair (i < j).
    template <class F> void forEachPair(F&& f) const {
        for (int i = 0; i < static_cast<int>(byBody_.size()); ++i)
            for (const Entry& e : byBody_[i])
                if (i < e.partner) f(i, e.partner, e.terrace);
    }

    std::size_t bytesReserved() const {
        std::size_t b = byBody_.capacity() * sizeof(byBody_[0]);
        for (const auto& v : byBody_)
            b += v.capacity() * sizeof(Entry);
        return b;
    }

private:
    struct Entry {
        std::int32_t partner;
        std::int32_t terrace;
    };
    void setOne(int i, int j, int terrace) {
        auto& list = byBody_[i];
        for (std::size_t k = 0; k < list.size(); ++k)
            if (list[k].partner == j) {
                if (terrace != 0) {
                    list[k].terrace = terrace;
                } else {
                    list[k] = list.back();
                    list.pop_back();
                }
                return;
            }
        if (terrace != 0) list.push_back({j, terrace});
    }

    std::vector<std::vector<Entry>> byBody_;
};

} // namespace terrace::dmd
