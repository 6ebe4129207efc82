#ifndef MESHGAP_EXCEPTION_H
#define MESHGAP_EXCEPTION_H

#include <stdexcept>
#include <string>

namespace meshgap
{
    /** \brief The one error type meshgap throws: "where: what", where \e where names the file (and line) or
        the part at fault. Executables catch it once in main, print it, and exit non-zero. */
    class Exception : public std::runtime_error
    {
    public:
        Exception(const std::string &where, const std::string &what) : std::runtime_error(where + ": " + what)
        {
        }
    };
}  // namespace meshgap

#endif
