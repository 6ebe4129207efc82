// Checked by tests/tools/unique_test_names.py with FirstCase.cpp.
namespace outer
{
    namespace
    {
        constexpr double LIMIT = 4.0;
        double helper(double x) { return x * LIMIT; }
        template <typename T>
        T secondOnly(T x)
        {
            return x;
        }
    }  // namespace
}  // namespace outer
