#ifndef MESHGAP_REGISTRY_H
#define MESHGAP_REGISTRY_H

#include <string>
#include <utility>
#include <vector>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"

namespace meshgap
{
    /** \brief The one lookup shape of the factories (solvers, planners, samplers): names, each with what makes
        its object, in the order of the table given (the order names() lists them in). */
    template <typename Factory>
    class Registry
    {
    public:
        /** \brief \e kind names what a name stands for in the error of at() ("algorithm", "planner", ...). */
        Registry(std::string kind, std::vector<std::pair<std::string, Factory>> entries)
            : kind_(std::move(kind)), entries_(std::move(entries))
        {
        }

        std::vector<std::string> names() const
        {
            std::vector<std::string> names;
            for (const auto &entry : entries_)
                names.push_back(entry.first);
            return names;
        }

        /** \brief The factory of \e name; throws meshgap::Exception(\e where, "unknown KIND 'name'; valid names:
            ...") for a name not in the table. */
        const Factory &at(const std::string &name, const std::string &where) const
        {
            for (const auto &entry : entries_)
                if (entry.first == name)
                    return entry.second;
            throw Exception(where, "unknown " + kind_ + " '" + name + "'; valid names: " + joinNames(names()));
        }

    private:
        std::string kind_;
        std::vector<std::pair<std::string, Factory>> entries_;
    };
}  // namespace meshgap

#endif
