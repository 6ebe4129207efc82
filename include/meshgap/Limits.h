#ifndef MESHGAP_LIMITS_H
#define MESHGAP_LIMITS_H

namespace meshgap
{
    /** \brief The largest magnitude meshgap takes for a coordinate, a position, a length or a size, in any unit.
        Readers refuse larger numbers (a mesh vertex, a pose, a URDF origin or box, a problem's start) with an error
        naming the value: beyond it double geometry gives wrong answers rather than imprecise ones (the exact tests
        multiply coordinates, so 1e300 overflows to infinity; and a position's last bit, 1e-4 at 1e12, is already
        coarser than most clearances). 1e12 metres is seven times the distance to the sun. */
    constexpr double MAX_MAGNITUDE = 1e12;
}  // namespace meshgap

#endif
