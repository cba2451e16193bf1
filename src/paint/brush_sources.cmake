target_sources(adaptex_paint PRIVATE placeholder.cpp)
