#pragma once
// The analysis' accumulators as bytes, for restart files (cli/restart.hpp): a run continued from
// them goes on adding to exactly the sums an uninterrupted run holds, so every number is kept as
// its raw bytes (native byte order: a restart file is read back by the build that wrote it).
// Every array is stored whole, zeros and all, so that the state's size is fixed by the analysis'
// settings from its first sample to its last: a restart file does not grow with the run.
//
// Every array's length is recorded and must be the one the reading analysis was built with, so a
// state from an analysis of other settings is refused (std::invalid_argument), not misread.
#include <complex>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace terrace::analysis {

class StateWriter {
public:
    template <class T> void value(const T& x) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto* p = reinterpret_cast<const std::uint8_t*>(&x);
        out_.insert(out_.end(), p, p + sizeof x);
    }
    /// A length, then the values raw, one by one (integers, flags).
    template <class T> void raw(const std::vector<T>& xs) {
        value(std::uint64_t(xs.size()));
        for (const T& x : xs)
            value(x);
    }
    void doubles(const double* xs, std::size_t n) {
        value(std::uint64_t(n));
        const auto* p = reinterpret_cast<const std::uint8_t*>(xs);
        out_.insert(out_.end(), p, p + n * sizeof(double));
    }
    void doubles(const std::vector<double>& xs) { doubles(xs.data(), xs.size()); }
    void doubles(const std::vector<std::complex<double>>& xs) {
        // std::complex<double> is an array of two doubles (C++ [complex.numbers]).
        doubles(reinterpret_cast<const double*>(xs.data()), 2 * xs.size());
    }
    void nested(const std::vector<std::vector<double>>& xs) {
        value(std::uint64_t(xs.size()));
        for (const auto& x : xs)
            doubles(x);
    }
    std::vector<std::uint8_t> take() { return std::move(out_); }

private:
    std::vector<std::uint8_t> out_;
};

/// Reads what a StateWriter wrote, in the same order, into arrays already of their lengths;
/// std::invalid_argument, naming `what`, where the bytes do not fit them.
class StateReader {
public:
    explicit StateReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

    template <class T> T value(const char* what) {
        static_assert(std::is_trivially_copyable_v<T>);
        T x;
        std::memcpy(&x, take(sizeof x, what), sizeof x);
        return x;
    }
    template <class T> void raw(std::vector<T>& xs, const char* what) {
        length(xs.size(), what);
        for (T& x : xs)
            x = value<T>(what);
    }
    void doubles(double* xs, std::size_t n, const char* what) {
        length(n, what);
        if (n > 0) std::memcpy(xs, take(n * sizeof(double), what), n * sizeof(double));
    }
    void doubles(std::vector<double>& xs, const char* what) { doubles(xs.data(), xs.size(), what); }
    void doubles(std::vector<std::complex<double>>& xs, const char* what) {
        doubles(reinterpret_cast<double*>(xs.data()), 2 * xs.size(), what);
    }
    void nested(std::vector<std::vector<double>>& xs, const char* what) {
        length(xs.size(), what);
        for (auto& x : xs)
            doubles(x, what);
    }
    /// The bytes were all read: more is not a state of this analysis.
    void finish() const {
        if (at_ != bytes_.size())
            throw std::invalid_argument("analysis state: " + std::to_string(bytes_.size() - at_) +
                                        " bytes beyond its end");
    }

private:
    void length(std::size_t expected, const char* what) {
        const auto n = value<std::uint64_t>(what);
        if (n != expected)
            fail(what, "holds " + std::to_string(n) + " values where this analysis has " +
                           std::to_string(expected));
    }
    const std::uint8_t* take(std::size_t size, const char* what) {
        if (size > bytes_.size() - at_) fail(what, "cut short");
        const std::uint8_t* p = bytes_.data() + at_;
        at_ += size;
        return p;
    }
    [[noreturn]] static void fail(const char* what, const std::string& why) {
        throw std::invalid_argument(std::string("analysis state: ") + what + " " + why +
                                    " (written for other analysis settings, or damaged)");
    }
    std::span<const std::uint8_t> bytes_;
    std::size_t at_ = 0;
};

} // namespace terrace::analysis
