// SplitMix64 (Steele, Lea & Flood 2014): the scene's procedural randomness. The forest for a
// seed must be the same on every machine, so figures from different weeks compare; <random>'s
// distributions leave their outputs to each library, this does not.
#pragma once

#include <cstdint>

namespace shadowkit::scene {

class SplitMix64 {
public:
    explicit SplitMix64(uint64_t seed) : m_state(seed) {}
    uint64_t next() {
        uint64_t z = (m_state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; } // [0, 1)
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

private:
    uint64_t m_state;
};

} // namespace shadowkit::scene
