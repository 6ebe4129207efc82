// Checked by tests/tools/unique_test_names.py (test unique_test_names_catches_shared): shares helper (an overload)
// and LIMIT with SecondCase.cpp; its other names, a using-declaration and what a comment or string says are its own.
#include <string>

namespace
{
    using std::string;
    const int LIMIT = 3;  // helper(int) in a comment
    struct FirstOnly
    {
        int helper() const { return 1; }
    };
    int helper(int x) { return x + LIMIT; }
    const auto twice = [](int x) { return 2 * x; };
}  // namespace

static std::string firstStatic() { return "namespace { int helper(double); }"; }
