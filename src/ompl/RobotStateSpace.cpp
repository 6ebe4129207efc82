#include "meshgap/ompl/RobotStateSpace.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>

#include <typeinfo>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"

namespace ob = ompl::base;

namespace meshgap
{
    namespace
    {
        /** \brief The OMPL space of one block of the robot's state; SE(2) and SE(3) positions within \e bounds. */
        ob::StateSpacePtr blockSpace(const StateBlock &block, const ob::RealVectorBounds &bounds)
        {
            switch (block.space)
            {
                case JointSpace::SE3:
                {
                    if (bounds.low.size() != 3)
                        throw Exception("robot state space", "'" + block.names[0] + "' moves free in SE(3): it needs "
                                                             "3-dimensional position bounds");
                    auto space = std::make_shared<ob::SE3StateSpace>();
                    space->setBounds(bounds);
                    return space;
                }
                case JointSpace::SE2:
                {
                    if (bounds.low.size() < 2)
                        throw Exception("robot state space", "'" + block.names[0] + "' moves free in SE(2): it needs "
                                                             "position bounds in x and y");
                    ob::RealVectorBounds planar(2);
                    for (int k = 0; k < 2; ++k)
                    {
                        planar.low[k] = bounds.low[k];
                        planar.high[k] = bounds.high[k];
                    }
                    auto space = std::make_shared<ob::SE2StateSpace>();
                    space->setBounds(planar);
                    return space;
                }
                case JointSpace::SO2:
                    return std::make_shared<ob::SO2StateSpace>();
                default:
                    break;
            }
            const auto count = static_cast<unsigned int>(block.names.size());
            auto vector = std::make_shared<ob::RealVectorStateSpace>(count);
            ob::RealVectorBounds limits(count);
            for (unsigned int k = 0; k < count; ++k)
            {
                limits.low[k] = block.lower[k];
                limits.high[k] = block.upper[k];
                vector->setDimensionName(k, block.names[k]);
            }
            vector->setBounds(limits);
            return vector;
        }

        enum class Kind
        {
            SE3,
            SE2,
            SO2,
            VECTOR,
            COMPOUND,
            OTHER
        };

        /** \brief What \e space is: OMPL's type tag (what OMPL's own code switches on) or, for a plain compound,
            its exact type, before any dynamic_cast (a state is walked at every validity check: the casts cost a
            tenth of a sampled check's instructions). */
        Kind kindOf(const ob::StateSpace &space)
        {
            switch (space.getType())
            {
                case ob::STATE_SPACE_SE3:
                    return Kind::SE3;
                case ob::STATE_SPACE_SE2:
                    return Kind::SE2;
                case ob::STATE_SPACE_SO2:
                    return Kind::SO2;
                case ob::STATE_SPACE_REAL_VECTOR:
                    return Kind::VECTOR;
                default:
                    break;
            }
            if (typeid(space) == typeid(ob::CompoundStateSpace))
                return Kind::COMPOUND;
            if (dynamic_cast<const ob::SE3StateSpace *>(&space))
                return Kind::SE3;
            if (dynamic_cast<const ob::SE2StateSpace *>(&space))
                return Kind::SE2;
            if (dynamic_cast<const ob::SO2StateSpace *>(&space))
                return Kind::SO2;
            if (dynamic_cast<const ob::RealVectorStateSpace *>(&space))
                return Kind::VECTOR;
            if (dynamic_cast<const ob::CompoundStateSpace *>(&space))
                return Kind::COMPOUND;
            return Kind::OTHER;
        }

        /** \brief Walk \e space's leaves in order, copying numbers out (\e out non-null) or in. */
        std::size_t walk(const ob::StateSpace &space, ob::State *state, double *out, const double *in)
        {
            const Kind kind = kindOf(space);
            auto copy = [&](double &value, std::size_t k)
            {
                if (out)
                    out[k] = value;
                else
                    value = in[k];
            };
            if (kind == Kind::SE3)
            {
                auto *s = state->as<ob::SE3StateSpace::StateType>();
                double *v[7] = {&s->as<ob::RealVectorStateSpace::StateType>(0)->values[0],
                                &s->as<ob::RealVectorStateSpace::StateType>(0)->values[1],
                                &s->as<ob::RealVectorStateSpace::StateType>(0)->values[2],
                                &s->rotation().x, &s->rotation().y, &s->rotation().z, &s->rotation().w};
                for (std::size_t k = 0; k < 7; ++k)
                    copy(*v[k], k);
                return 7;
            }
            if (kind == Kind::SE2)
            {
                auto *s = state->as<ob::SE2StateSpace::StateType>();
                if (out)
                {
                    out[0] = s->getX();
                    out[1] = s->getY();
                    out[2] = s->getYaw();
                }
                else
                {
                    s->setXY(in[0], in[1]);
                    s->setYaw(in[2]);
                }
                return 3;
            }
            if (kind == Kind::SO2)
            {
                copy(state->as<ob::SO2StateSpace::StateType>()->value, 0);
                return 1;
            }
            if (kind == Kind::VECTOR)
            {
                const auto *vector = space.as<ob::RealVectorStateSpace>();
                double *values = state->as<ob::RealVectorStateSpace::StateType>()->values;
                for (unsigned int k = 0; k < vector->getDimension(); ++k)
                    copy(values[k], k);
                return vector->getDimension();
            }
            if (kind == Kind::COMPOUND)
            {
                const auto *compound = space.as<ob::CompoundStateSpace>();
                std::size_t count = 0;
                for (unsigned int i = 0; i < compound->getSubspaceCount(); ++i)
                    count += walk(*compound->getSubspace(i), state->as<ob::CompoundState>()->components[i],
                                  out ? out + count : nullptr, in ? in + count : nullptr);
                return count;
            }
            throw Exception("robot state space", "space " + quote(space.getName()) +
                                                     " is none of SE(3), SE(2), SO(2), real vector or a compound");
        }

        /** \brief Numbers in a state of \e space (walk()'s count, without a state). */
        std::size_t countOf(const ob::StateSpace &space)
        {
            const Kind kind = kindOf(space);
            if (kind == Kind::SE3)
                return 7;
            if (kind == Kind::SE2)
                return 3;
            if (kind == Kind::SO2)
                return 1;
            if (kind == Kind::VECTOR)
                return space.as<ob::RealVectorStateSpace>()->getDimension();
            if (kind == Kind::COMPOUND)
            {
                const auto *compound = space.as<ob::CompoundStateSpace>();
                std::size_t count = 0;
                for (unsigned int i = 0; i < compound->getSubspaceCount(); ++i)
                    count += countOf(*compound->getSubspace(i));
                return count;
            }
            throw Exception("robot state space", "space " + quote(space.getName()) +
                                                     " is none of SE(3), SE(2), SO(2), real vector or a compound");
        }
    }  // namespace

    ob::StateSpacePtr robotStateSpace(const RobotModel &robot, const ob::RealVectorBounds &bounds)
    {
        auto space = std::make_shared<ob::CompoundStateSpace>();
        for (const StateBlock &block : robot.stateBlocks())
            space->addSubspace(blockSpace(block, bounds), 1.0);
        if (space->getSubspaceCount() == 0)
            throw Exception("robot state space", "the robot has no movable joint (a fixed robot): there is nothing "
                                                   "to plan; its clearance can still be asked");
        if (countOf(*space) != robot.dimension())
            throw Exception("robot state space", "the space's numbers do not match the robot's state");
        space->lock();
        return space;
    }

    void robotStateToVector(const ob::StateSpace &space, const ob::State *state, std::vector<double> &out)
    {
        out.resize(countOf(space));
        walk(space, const_cast<ob::State *>(state), out.data(), nullptr);
    }

    void robotStateFromVector(const ob::StateSpace &space, const std::vector<double> &values, ob::State *state)
    {
        const std::size_t count = countOf(space);
        if (values.size() != count)
            throw Exception("robot state space", std::to_string(values.size()) + " numbers for a state of " +
                                                     std::to_string(count));
        walk(space, state, nullptr, values.data());
    }
}  // namespace meshgap
