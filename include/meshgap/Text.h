#ifndef MESHGAP_TEXT_H
#define MESHGAP_TEXT_H

#include <cstddef>
#include <string>
#include <vector>

namespace meshgap
{
    /** \brief How many characters of user input an error message quotes (excerpt(), quote()). */
    constexpr std::size_t MAX_QUOTED = 200;

    /** \brief \e text as an error message may show it: whole when it has at most \e limit characters (bytes), else
        its first three quarters of \e limit and its last quarter around "..." (cut at UTF-8 character boundaries),
        followed by " (N characters)". A 30 MB line or a 5000-character path gives a short message that still shows
        how the value begins and ends (a path's file name). */
    std::string excerpt(const std::string &text, std::size_t limit = MAX_QUOTED);

    /** \brief \e text in single quotes, as every error message that echoes user input (a value, a name, a line, a
        path) quotes it: "'text'", or for a long text "'first...last' (N characters)" (excerpt()). */
    std::string quote(const std::string &text, std::size_t limit = MAX_QUOTED);

    /** \brief The one strict number parser: true and \e value if all of \e text is a number in std::strtod's
        syntax (no leading or trailing characters, so "1.5x" and "" fail); NaN and infinities parse (check
        std::isfinite() where they are not allowed). */
    bool parseNumber(const std::string &text, double &value);

    /** \brief parseNumber() for a finite number; otherwise throws meshgap::Exception(\e where, "'text' is not a finite
        number" followed by " (expected ...)" when \e expected is given). */
    double parseFiniteNumber(const std::string &text, const std::string &where, const std::string &expected = "");

    /** \brief True and \e value if all of \e text is a decimal whole number (digits only, no sign) that fits. */
    bool parseUnsigned(const std::string &text, unsigned long &value);

    /** \brief The items of a comma-separated list, each trimmed of white space; empty items are dropped. */
    std::vector<std::string> splitList(const std::string &list);

    /** \brief Names joined by ", " (for "valid names: a, b, c" messages and --help texts). */
    std::string joinNames(const std::vector<std::string> &names);
}  // namespace meshgap

#endif
