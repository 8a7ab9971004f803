// Wall-clock and calling-thread CPU time of a stretch of code. The thread's CPU time is
// what separates culling's own cost from the driver's: on llvmpipe the rasteriser's threads
// share the cores with ours, so wall-clock time of even pure CPU code swells with them.
#pragma once

#include <chrono>
#include <ctime>

namespace shadowkit::gl {

struct CpuTimes {
    double wallMilliseconds = 0.0;
    double threadMilliseconds = 0.0; // CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID)

    CpuTimes& operator+=(const CpuTimes& o) {
        wallMilliseconds += o.wallMilliseconds;
        threadMilliseconds += o.threadMilliseconds;
        return *this;
    }
};

class Stopwatch {
public:
    Stopwatch() : m_wall(std::chrono::steady_clock::now()), m_thread(threadNow()) {}
    CpuTimes elapsed() const {
        return {std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - m_wall).count(),
                threadNow() - m_thread};
    }

private:
    static double threadNow() {
        timespec t{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
        return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
    }
    std::chrono::steady_clock::time_point m_wall;
    double m_thread;
};

} // namespace shadowkit::gl
