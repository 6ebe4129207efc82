#include "meshgap/Text.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "meshgap/Exception.h"

namespace meshgap
{
    namespace
    {
        /** \brief excerpt() with the quotes of quote() around the text shown, before the length. */
        std::string shorten(const std::string &text, std::size_t limit, const char *quotes)
        {
            if (text.size() <= limit)
                return quotes + text + quotes;
            auto continuation = [&text](std::size_t i) { return (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80; };
            std::size_t head = limit - limit / 4, tail = text.size() - limit / 4;
            while (head > 0 && continuation(head))
                --head;
            while (tail < text.size() && continuation(tail))
                ++tail;
            return quotes + text.substr(0, head) + "..." + text.substr(tail) + quotes + " (" +
                   std::to_string(text.size()) + " characters)";
        }
    }  // namespace

    std::string excerpt(const std::string &text, std::size_t limit)
    {
        return shorten(text, limit, "");
    }

    std::string quote(const std::string &text, std::size_t limit)
    {
        return shorten(text, limit, "'");
    }

    bool parseNumber(const std::string &text, double &value)
    {
        if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())))
            return false;
        char *end = nullptr;
        errno = 0;
        const double x = std::strtod(text.c_str(), &end);
        if (end != text.c_str() + text.size() || errno == ERANGE)
            return false;
        value = x;
        return true;
    }

    double parseFiniteNumber(const std::string &text, const std::string &where, const std::string &expected)
    {
        double x = 0.0;
        if (!parseNumber(text, x) || !std::isfinite(x))
            throw Exception(where, quote(text) + " is not a finite number" +
                                       (expected.empty() ? std::string() : " (expected " + expected + ")"));
        return x;
    }

    bool parseUnsigned(const std::string &text, unsigned long &value)
    {
        if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
            return false;
        char *end = nullptr;
        errno = 0;
        const unsigned long x = std::strtoul(text.c_str(), &end, 10);
        if (errno == ERANGE)
            return false;
        value = x;
        return true;
    }

    std::vector<std::string> splitList(const std::string &list)
    {
        std::vector<std::string> items;
        std::string::size_type begin = 0;
        while (begin <= list.size())
        {
            std::string::size_type end = list.find(',', begin);
            if (end == std::string::npos)
                end = list.size();
            const std::string item = list.substr(begin, end - begin);
            const auto first = item.find_first_not_of(" \t\r\n");
            if (first != std::string::npos)
                items.push_back(item.substr(first, item.find_last_not_of(" \t\r\n") - first + 1));
            begin = end + 1;
        }
        return items;
    }

    std::string joinNames(const std::vector<std::string> &names)
    {
        std::string out;
        for (const std::string &name : names)
            out += (out.empty() ? "" : ", ") + name;
        return out;
    }
}  // namespace meshgap
