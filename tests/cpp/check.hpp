// The C++ tests' one assertion: CHECK(condition, what) counts a pass or prints the failure and
// counts it; each test program reports `passes` and `failures` and exits non-zero on a failure.
#pragma once

#include <cstdio>
#include <string>

static int failures = 0, passes = 0;
#define CHECK(cond, what)                                                                                \
    do {                                                                                                 \
        if (cond) {                                                                                      \
            ++passes;                                                                                    \
        } else {                                                                                         \
            ++failures;                                                                                  \
            std::printf("FAIL %s:%d: %s  [%s]\n", __FILE__, __LINE__, std::string(what).c_str(), #cond); \
        }                                                                                                \
    } while (0)

// SKIP(what): a check that cannot run here (e.g. the AVX2 kernel on a CPU without AVX2 + FMA) is
// reported as skipped, never counted as a pass; the program's summary line says how many.
inline int skips = 0;
#define SKIP(what)                                                               \
    do {                                                                         \
        ++skips;                                                                 \
        std::printf("SKIPPED %s:%d: %s\n", __FILE__, __LINE__, std::string(what).c_str()); \
    } while (0)
