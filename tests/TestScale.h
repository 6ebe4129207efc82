#ifndef MESHGAP_TESTS_TEST_SCALE_H
#define MESHGAP_TESTS_TEST_SCALE_H

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace meshgap::test
{
    /** \brief The share, in (0, 1], of its random states, motions, seeds or poses that a heavy randomized test
        checks: 1 (all of them) unless the environment variable MESHGAP_TEST_SCALE says less. tests/sanitizers.sh
        sets it for the instrumented runs, where a memory or undefined-behaviour error shows on any state and each
        state costs 10 to 100 times more; the Release run keeps the full counts, so no oracle coverage is lost.
        Any other value than a number in (0, 1] throws, naming the variable and the value. */
    inline double scale()
    {
        const char *text = std::getenv("MESHGAP_TEST_SCALE");
        if (text == nullptr || *text == '\0')
            return 1.0;
        char *end = nullptr;
        const double value = std::strtod(text, &end);
        if (*end != '\0' || !(value > 0.0 && value <= 1.0))
            throw std::invalid_argument(std::string("MESHGAP_TEST_SCALE='") + text +
                                        "': not a number in (0, 1] (the share of the random cases checked)");
        return value;
    }

    /** \brief \e full scaled by scale(), rounded up, and at least \e least (a test whose own checks need so many,
        e.g. "more than 10 rejected", stays able to pass and to fail). */
    inline int scaled(int full, int least = 1)
    {
        return std::max(std::min(least, full), static_cast<int>(std::ceil(full * scale())));
    }

    /** \brief scaled(full, least), and at most \e most (but at least \e least) under scale() < 1: \e full at full
        scale. For a test whose items each cost so much instrumented that a share of them is still many. */
    inline int scaledAtMost(int full, int most, int least = 1)
    {
        return scale() < 1.0 ? std::min(scaled(full, least), std::max(most, least)) : full;
    }

    /** \brief Every how many items of a sequence whose order matters (a motion's poses, with a warm start carried
        along) the expensive oracle looks: 1 at full scale, about 1 / scale() otherwise. */
    inline int stride()
    {
        return std::max(1, static_cast<int>(std::lround(1.0 / scale())));
    }
}  // namespace meshgap::test

#endif
