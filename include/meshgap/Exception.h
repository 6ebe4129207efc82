#ifndef MESHGAP_EXCEPTION_H
#define MESHGAP_EXCEPTION_H

#include <stdexcept>
#include <string>

#include "meshgap/Text.h"

namespace meshgap
{
    /** \brief The longest message an Exception keeps: its places quote user input short (quote(), excerpt()); this
        is the last resort for text that reaches a message some other way. */
    constexpr std::size_t MAX_MESSAGE = 4000;

    /** \brief The one error type meshgap throws: "where: what", where \e where names the file (and line) or
        the part at fault. Executables catch it once in main, print it, and exit non-zero. A message longer than
        MAX_MESSAGE keeps its beginning and end (excerpt()). */
    class Exception : public std::runtime_error
    {
    public:
        Exception(const std::string &where, const std::string &what)
          : std::runtime_error(excerpt(where + ": " + what, MAX_MESSAGE))
        {
        }
    };
}  // namespace meshgap

#endif
