#ifndef MESHGAP_TESTS_TEST_NOTE_H
#define MESHGAP_TESTS_TEST_NOTE_H

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace meshgap::test
{
    /** \brief A line on what a test saw (counts, worst cases), recorded as the test's "note" property in gtest's
        XML report instead of printed: test::Note() << "..." << value; records it when the statement ends. */
    class Note
    {
    public:
        Note() = default;
        Note(const Note &) = delete;
        Note &operator=(const Note &) = delete;
        ~Note() { ::testing::Test::RecordProperty("note", text_.str()); }

        template <typename T>
        Note &operator<<(const T &value)
        {
            text_ << value;
            return *this;
        }

    private:
        std::ostringstream text_;
    };
}  // namespace meshgap::test

#endif
