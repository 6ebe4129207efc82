// libFuzzer entry for fuzz::moveit() (see FuzzTargets.h).
#include "FuzzTargets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    meshgap::fuzz::moveit(data, size);
    return 0;
}
