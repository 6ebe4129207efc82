#ifndef MESHGAP_TEXT_H
#define MESHGAP_TEXT_H

#include <string>
#include <vector>

namespace meshgap
{
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
