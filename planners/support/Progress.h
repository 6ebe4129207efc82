#ifndef MESHGAP_PLANNERS_SUPPORT_PROGRESS_H
#define MESHGAP_PLANNERS_SUPPORT_PROGRESS_H

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <mutex>
#include <ompl/base/Planner.h>
#include <string>
#include <thread>

namespace meshgap
{
    namespace cli
    {
        /** \brief One stderr line a second while the planner runs: elapsed time, validity checks, and the planner's
            iterations and best cost when it reports them (OMPL's planner progress properties, read from this thread
            as ompl::tools::Benchmark does). \e validityCount gives the checks made so far (the checker's counter,
            read from this thread). */
        class Progress
        {
        public:
            Progress(const ompl::base::PlannerPtr &planner, std::function<std::uint64_t()> validityCount, bool enabled)
            {
                if (!enabled)
                    return;
                thread_ = std::thread([this, planner, validityCount] {
                    const auto start = std::chrono::steady_clock::now();
                    const auto properties = planner->getPlannerProgressProperties();
                    std::unique_lock<std::mutex> lock(mutex_);
                    while (!cv_.wait_for(lock, std::chrono::seconds(1), [this] { return done_; }))
                    {
                        const double elapsed =
                            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                        std::string line = "planning: " + std::to_string(static_cast<int>(elapsed + 0.5)) + " s, " +
                                           std::to_string(validityCount()) + " validity checks";
                        for (const char *name : {"iterations INTEGER", "best cost REAL"})
                        {
                            const auto it = properties.find(name);
                            if (it == properties.end())
                                continue;
                            const std::string value = it->second();
                            const std::string label = std::string(name).substr(0, std::string(name).rfind(' '));
                            if (!value.empty() && value != "nan" && value != "inf" && value != "-inf")
                                line += ", " + label + " " + value;
                        }
                        std::fprintf(stderr, "%s\n", line.c_str());
                    }
                });
            }
            ~Progress()
            {
                if (!thread_.joinable())
                    return;
                {
                    std::lock_guard<std::mutex> lock(mutex_);
                    done_ = true;
                }
                cv_.notify_all();
                thread_.join();
            }

        private:
            std::mutex mutex_;
            std::condition_variable cv_;
            bool done_{false};
            std::thread thread_;
        };
    }  // namespace cli
}  // namespace meshgap

#endif
