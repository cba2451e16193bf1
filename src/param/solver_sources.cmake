target_sources(adaptex_param PRIVATE placeholder.cpp)
