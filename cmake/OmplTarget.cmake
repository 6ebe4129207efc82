# Debian's OMPL 1.5.2 exports variables (OMPL_INCLUDE_DIRS, OMPL_LIBRARIES) and no
# imported target. This file is the one place that wraps them in `ompl::ompl`;
# meshgapConfig.cmake includes it too, so consumers see the same target.
if(NOT TARGET ompl::ompl)
    if(TARGET ompl)
        add_library(ompl::ompl INTERFACE IMPORTED)
        set_target_properties(ompl::ompl PROPERTIES INTERFACE_LINK_LIBRARIES ompl)
    else()
        add_library(ompl::ompl INTERFACE IMPORTED)
        set_target_properties(ompl::ompl PROPERTIES
            INTERFACE_INCLUDE_DIRECTORIES "${OMPL_INCLUDE_DIRS}"
            INTERFACE_LINK_LIBRARIES "${OMPL_LIBRARIES}")
    endif()
endif()
