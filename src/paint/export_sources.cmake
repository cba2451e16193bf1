# target_sources(adaptex_paint PRIVATE ...) for decal / export
