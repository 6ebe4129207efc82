#ifndef MESHGAP_CLASS_FORWARD_H
#define MESHGAP_CLASS_FORWARD_H

#include <memory>

/** \brief Declare class C with C##Ptr and C##ConstPtr shared-pointer aliases (as OMPL_CLASS_FORWARD). */
#define MESHGAP_CLASS_FORWARD(C)                                                                                       \
    class C;                                                                                                           \
    using C##Ptr = std::shared_ptr<C>;                                                                                 \
    using C##ConstPtr = std::shared_ptr<const C>

#endif
